// GPU culling, the groups' bounds (GroupBounds): one work group per group of 256 places of the draw
// order whose places or decals changed since its bounds were written (all of them after a new
// layout). Each invocation reads one place's decal and takes the box of its object (the first free
// one for an object the group has no box for yet), which holds every such decal's bounding sphere
// in the object's space, rounded outward. A group whose decals lie on more objects than it has
// boxes, or holds one the culling must count (the host's, or one that cannot be drawn), is left to
// the test by place.
#include "projector.glsl"
#include "cull_layout.glsl"
#include "cull_decal.glsl"
#include "cull_group_bounds.glsl"

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count;  // places
layout(location = 1) uniform uint u_listed; // 0: work group w is group w; 1: the groups listed

layout(std430, binding = 0) readonly buffer Listed {
    uint listedGroups[];
};

shared uint sLow[kGroupBoxes * 3u], sHigh[kGroupBoxes * 3u]; // the boxes as ordered keys (key())
shared uint sObjects[kGroupBoxes], sByPlace;

// A float as an unsigned key in the same order.
uint key(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

float unkey(uint k) {
    return uintBitsToFloat((k & 0x80000000u) != 0u ? k & 0x7fffffffu : ~k);
}

// Whether the projector draws decal `i` on object `object` when its object is in view (the test by
// place would find it neither the host's nor one that cannot be drawn).
bool plainDecal(uint i, uint object, float radius, vec3 center) {
    uint type = decalBodies[i].look & 0xffffu;
    bool drawable = type < uint(decalTypes.length()) && decalTypes[type].info.z == 1u;
    bool finite = !any(isnan(center)) && !any(isinf(center)) && !isinf(radius);
    return drawable && finite && radius > 0.0 && float(object) < u_params.y;
}

// The box of `object`, taken if the group has none for it yet; kGroupBoxes when every box is taken.
uint boxOf(uint object) {
    for (uint k = 0u; k < kGroupBoxes; ++k) {
        uint held = atomicCompSwap(sObjects[k], 0xffffffffu, object);
        if (held == 0xffffffffu || held == object) return k;
    }
    return kGroupBoxes;
}

void addDecal(uint i) {
    DecalBounds b = decalBounds[i];
    uint object = boundsObject(i, b);
    float radius = boundsRadius(b);
    uint k = plainDecal(i, object, radius, b.center) ? boxOf(object) : kGroupBoxes;
    if (k == kGroupBoxes) {
        atomicOr(sByPlace, 1u);
        return;
    }
    for (uint a = 0u; a < 3u; ++a) {
        atomicMin(sLow[k * 3u + a], key(b.center[a] - radius));
        atomicMax(sHigh[k * 3u + a], key(b.center[a] + radius));
    }
}

// Box `k` of the group from the shared keys, rounded outward: the sums above and the halving each
// round by half a unit in the last place.
GroupBox groupBox(uint k) {
    GroupBox g;
    g.object = sObjects[k];
    g.state = sByPlace != 0u ? (k == 0u ? kBoxByPlace : kBoxUnused)
              : g.object == 0xffffffffu ? kBoxUnused : kBoxUsed;
    vec3 low = vec3(unkey(sLow[k * 3u]), unkey(sLow[k * 3u + 1u]), unkey(sLow[k * 3u + 2u]));
    vec3 high = vec3(unkey(sHigh[k * 3u]), unkey(sHigh[k * 3u + 1u]), unkey(sHigh[k * 3u + 2u]));
    g.center = 0.5 * (low + high);
    g.extent = 0.5 * (high - low) * 1.00001 + 2e-6 * max(abs(low), abs(high));
    if (g.state != kBoxUsed) g.center = g.extent = vec3(0.0);
    return g;
}

void main() {
    uint t = gl_LocalInvocationIndex;
    uint group = u_listed != 0u ? listedGroups[gl_WorkGroupID.x] : gl_WorkGroupID.x;
    if (t < kGroupBoxes * 3u) {
        sLow[t] = 0xffffffffu;
        sHigh[t] = 0u;
    }
    if (t < kGroupBoxes) sObjects[t] = 0xffffffffu;
    if (t == 0u) sByPlace = 0u;
    barrier();
    uint place = group * kGroupPlaces + t;
    uint entry = place < u_count ? drawOrder[place] : 0xffffffffu;
    if (entry != 0xffffffffu) addDecal(entry);
    barrier();
    if (t < kGroupBoxes) groupBoxes[group * kGroupBoxes + t] = groupBox(t);
}
