// GPU culling, the groups' bounds (GroupBounds): one work group per group of 256 places of the draw
// order whose places or decals changed since its bounds were written (all of them after a new
// layout). Each invocation reads one place's decal; the group's box in its object's space holds every
// decal's bounding sphere, rounded outward. A group whose decals lie on several objects, or holds one
// the culling must count (the host's, or one that cannot be drawn), is left to the test by place.
#include "projector.glsl"
#include "cull_layout.glsl"
#include "cull_group_bounds.glsl"

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count;  // places
layout(location = 1) uniform uint u_listed; // 0: work group w is group w; 1: the groups listed

layout(std430, binding = 0) readonly buffer Listed {
    uint listedGroups[];
};

shared uint sLow[3], sHigh[3]; // the box as ordered keys (key())
shared uint sObjectLow, sObjectHigh, sDecals, sByPlace;

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

void addDecal(uint i) {
    DecalBounds b = decalBounds[i];
    uint object = b.objectRadius & 0xffffu;
    if (u_params.y > 65536.0) object = decalObject(b.objectRadius, decalBodies[i].look);
    float radius = uintBitsToFloat(b.objectRadius & 0xffff0000u);
    atomicAdd(sDecals, 1u);
    if (!plainDecal(i, object, radius, b.center)) {
        atomicOr(sByPlace, 1u);
        return;
    }
    atomicMin(sObjectLow, object);
    atomicMax(sObjectHigh, object);
    for (int k = 0; k < 3; ++k) {
        atomicMin(sLow[k], key(b.center[k] - radius));
        atomicMax(sHigh[k], key(b.center[k] + radius));
    }
}

void main() {
    uint t = gl_LocalInvocationIndex;
    uint group = u_listed != 0u ? listedGroups[gl_WorkGroupID.x] : gl_WorkGroupID.x;
    if (t < 3u) {
        sLow[t] = 0xffffffffu;
        sHigh[t] = 0u;
    }
    if (t == 0u) {
        sObjectLow = 0xffffffffu;
        sObjectHigh = sDecals = sByPlace = 0u;
    }
    barrier();
    uint place = group * kGroupPlaces + t;
    uint entry = place < u_count ? drawOrder[place] : 0xffffffffu;
    if (entry != 0xffffffffu) addDecal(entry);
    barrier();
    if (t != 0u) return;
    GroupBound g;
    g.object = sObjectLow;
    g.state = sDecals == 0u ? kGroupEmpty : sByPlace != 0u || sObjectLow != sObjectHigh ? kGroupByPlace
                                                                                         : kGroupPlain;
    vec3 low = vec3(unkey(sLow[0]), unkey(sLow[1]), unkey(sLow[2]));
    vec3 high = vec3(unkey(sHigh[0]), unkey(sHigh[1]), unkey(sHigh[2]));
    // Rounded outward: the sums above and the halving each round by half a unit in the last place.
    g.center = 0.5 * (low + high);
    g.extent = 0.5 * (high - low) * 1.00001 + 2e-6 * max(abs(low), abs(high));
    if (g.state != kGroupPlain) g.center = g.extent = vec3(0.0);
    groupBounds[group] = g;
}
