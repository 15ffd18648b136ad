// GPU culling, pass 2 (GpuCulling): the places of the groups cull_groups.comp listed, a work group each,
// dispatched indirectly by their count, or of every group where most were listed in an earlier frame
// (u_every: no pass before it, no indirect dispatch to wait for; each work group culls its group whole as
// cull_groups.comp would, or counts it tested), an invocation a place. It counts the decals the host draws
// itself and those that cannot be drawn, culls the boxes whose bounding sphere lies outside the view's side
// planes (from each decal's 16-byte bounds alone: no body to read, no frame to unpack, no corners), and lists
// the other places as candidates for the exact test (cull_exact.comp), in the visible list's buffer, which
// the last pass overwrites. The exact test leaves each candidate's decal index in its slot, so that past the
// visible count the buffer holds decal indices, as a reader with an earlier count (the renderer's box
// overlay) expects. It also clears its group's class bits for the passes after it.
#include "projector.glsl"
#include "cull_layout.glsl"
#include "cull_decal.glsl"
#include "cull_group_bounds.glsl"
#include "cull_group_test.glsl"

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count; // places
// 1 when a type is not drawn by the projector (the host draws it, or it cannot be drawn) or a decal
// may name a type that does not exist: then the test reads each decal's type from its body.
layout(location = 1) uniform uint u_checkTypes;
layout(location = 2) uniform uint u_groups; // of the draw order
layout(location = 3) uniform uint u_every;  // 1: work group w tests group w

layout(std430, binding = 0) writeonly buffer Classes {
    uint classBits[]; // bit k of word w: place 32 w + k is visible (set by cull_exact.comp)
};
layout(std430, binding = 7) writeonly buffer Candidates {
    uint candidates[];
};

shared uint sCandidates, sFirst;
shared bool sTested; // the group needs the test by place
shared uint sCounts[2]; // the work group's invalid and host-drawn decals

const uint kCulled = 0u, kCandidate = 1u, kInvalid = 2u, kHostDrawn = 3u;

// An upper bound of how far `m` stretches a vector: the root of the largest row sum of absolute
// values of its columns' Gram matrix (Gershgorin), the longest column where they are orthogonal.
float largestStretch(mat3 m) {
    float largest = 0.0;
    for (int i = 0; i < 3; ++i)
        largest = max(largest, dot(m[i], m[i]) + abs(dot(m[i], m[(i + 1) % 3])) + abs(dot(m[i], m[(i + 2) % 3])));
    return sqrt(largest);
}

// Whether the sphere around decal `b`'s box lies wholly outside one of the view's four side planes,
// with a margin for rounding, so that the exact test would cull the box too. The radius (what
// DecalBounds holds, at least the distance from the centre to the corners, |(hx + hz |sx|, hy + hz
// |sy|, hz)| for half extents h and slant s) is scaled by the model's largest stretch.
bool sphereOutside(DecalBounds b, float radius, ProjectorObject o) {
    radius *= largestStretch(mat3(o.model));
    vec4 c = vec4((o.model * vec4(b.center, 1.0)).xyz, 1.0);
    vec4 w = vec4(u_viewProj[0][3], u_viewProj[1][3], u_viewProj[2][3], u_viewProj[3][3]);
    for (int k = 0; k < 4; ++k) {
        int row = k / 2;
        vec4 axis = vec4(u_viewProj[0][row], u_viewProj[1][row], u_viewProj[2][row], u_viewProj[3][row]);
        vec4 plane = (k & 1) == 0 ? w + axis : w - axis; // inside: dot(plane, c) >= 0
        float slack = radius * length(plane.xyz) * 1.001 + 1e-5 * dot(abs(plane), abs(c));
        if (dot(plane, c) < -slack) return true;
    }
    return false;
}

uint classify(uint i) {
    DecalBounds b = decalBounds[i];
    uint object = boundsObject(i, b);
    bool objectKnown = float(object) < u_params.y, hostType = false, typeDrawable = true;
    if (u_checkTypes != 0u) { // otherwise every type is drawn by the projector and every decal has one
        uint type = decalBodies[i].look & 0xffffu;
        bool known = type < uint(decalTypes.length());
        hostType = known && decalTypes[type].info.z == 2u;
        typeDrawable = known && decalTypes[type].info.z != 0u;
    }
    // The host's decals, valid or not (it counts its invalid ones), then those that cannot be drawn.
    if (hostType || (objectKnown && objects[object].info.w != 0u)) return kHostDrawn;
    float radius = boundsRadius(b);
    if (!(radius > 0.0) || !typeDrawable || !objectKnown) return kInvalid;
    ProjectorObject o = objects[object];
    if (o.info.z != 0u || sphereOutside(b, radius, o)) return kCulled; // a collapsed object, or out of view
    return kCandidate;
}

// With u_every, what cull_groups.comp does for the group: clears its visible count (and its
// block's), and tells whether it needs the test by place (the scatter then looks at every group).
bool testsGroup(uint group) {
    if (u_every == 0u) return true; // listed
    groupData[group] = 0u;
    if (group % kBlockGroups == 0u) groupData[u_groups + group / kBlockGroups] = 0u;
    return byPlace(group);
}

void main() {
    uint t = gl_LocalInvocationIndex, w = gl_WorkGroupID.x;
    uint group = u_every != 0u ? w : groupData[listStart(u_groups) + w];
    if (t == 0u) {
        sCandidates = 0u;
        sTested = testsGroup(group);
    }
    if (t < 2u) sCounts[t] = 0u;
    uint place = group * kGroupPlaces + t;
    uint entry = place < u_count ? drawOrder[place] : 0xffffffffu; // an empty place
    uint c = entry != 0xffffffffu ? classify(entry) : kCulled;  // while the group is tested
    barrier();
    if (!sTested) { // culled whole: its places are not candidates, its count stays 0
        if (t == 0u && u_every != 0u) atomicAdd(tested.groupsX, 1u); // the few culled whole are counted
        return;
    }
    uint rank = 0u;
    if (c == kCandidate) rank = atomicAdd(sCandidates, 1u);
    else if (c != kCulled) atomicAdd(sCounts[c - kInvalid], 1u);
    barrier();
    if (t == 0u) {
        if (sCandidates != 0u) sFirst = atomicAdd(candidateCount, sCandidates);
        if (sCounts[0] != 0u) atomicAdd(invalidCount, sCounts[0]);
        if (sCounts[1] != 0u) atomicAdd(hostDrawnCount, sCounts[1]);
    }
    if (t < kGroupPlaces / 32u) classBits[group * (kGroupPlaces / 32u) + t] = 0u;
    barrier();
    if (c == kCandidate) candidates[sFirst + rank] = place;
}
