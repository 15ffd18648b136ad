// GPU culling, pass 1 of 3 (GpuCulling): one invocation per place of the draw order. It counts the
// decals the host draws itself and those that cannot be drawn, culls the boxes whose bounding sphere
// lies outside the view's side planes (no frame to unpack, no corners: most of a large world), and
// lists the other places as candidates for the exact test (cull_exact.comp), in the visible list's
// buffer, which the last pass overwrites. The exact test leaves each candidate's decal index in its
// slot, so that past the visible count the buffer holds decal indices, as a reader with an earlier
// count (the renderer's box overlay) expects. It also clears its group's class bits and count for the
// passes after it.
#include "projector.glsl"
#include "cull_layout.glsl"

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count; // places

layout(std430, binding = 0) writeonly buffer Classes {
    uint classBits[]; // bit k of word w: place 32 w + k is visible (set by cull_exact.comp)
};
layout(std430, binding = 7) writeonly buffer Candidates {
    uint candidates[];
};

shared uint sCandidates, sFirst;
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

// Whether the sphere around record `r`'s box lies wholly outside one of the view's four side planes,
// with a margin for rounding, so that the exact test would cull the box too. Corners lie at most
// |(hx + hz |sx|, hy + hz |sy|, hz)| from the centre (half extents h, slant s: the depth axis is
// normal + sx tangent + sy bitangent), times the model's largest stretch.
bool sphereOutside(DecalRecord r, ProjectorObject o) {
    vec2 slant = abs(unpackHalf2x16(r.info.z));
    float hz = r.centerDepth.w;
    float radius = length(vec3(r.halfSize + hz * slant, hz)) * largestStretch(mat3(o.model));
    vec4 c = vec4((o.model * vec4(r.centerDepth.xyz, 1.0)).xyz, 1.0);
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
    DecalRecord r = decalRecords[i];
    uint type = decalTypeIndex(r);
    bool typeKnown = type < uint(decalTypes.length()), objectKnown = float(r.info.x) < u_params.y;
    // The host's decals, valid or not (it counts its invalid ones), then those that cannot be drawn.
    if ((typeKnown && decalTypes[type].info.z == 2u) || (objectKnown && objects[r.info.x].info.w != 0u))
        return kHostDrawn;
    if (!decalRecordValid(r) || !typeKnown || decalTypes[type].info.z == 0u || !objectKnown) return kInvalid;
    ProjectorObject o = objects[r.info.x];
    if (o.info.z != 0u || sphereOutside(r, o)) return kCulled; // a collapsed object, or out of view
    return kCandidate;
}

void main() {
    uint t = gl_LocalInvocationIndex, group = gl_WorkGroupID.x;
    if (t == 0u) sCandidates = 0u;
    if (t < 2u) sCounts[t] = 0u;
    barrier();
    uint place = gl_GlobalInvocationID.x;
    uint entry = place < u_count ? drawOrder[place] : 0xffffffffu; // an empty place
    uint c = entry != 0xffffffffu ? classify(entry) : kCulled;
    uint rank = 0u;
    if (c == kCandidate) rank = atomicAdd(sCandidates, 1u);
    else if (c != kCulled) atomicAdd(sCounts[c - kInvalid], 1u);
    barrier();
    if (t == 0u) {
        if (sCandidates != 0u) {
            sFirst = atomicAdd(candidateCount, sCandidates);
            atomicMax(exact.x, (sFirst + sCandidates + kCandidateGroup - 1u) / kCandidateGroup);
        }
        if (sCounts[0] != 0u) atomicAdd(invalidCount, sCounts[0]);
        if (sCounts[1] != 0u) atomicAdd(hostDrawnCount, sCounts[1]);
        groupData[group] = 0u;
    }
    if (t < kGroupPlaces / 32u) classBits[group * (kGroupPlaces / 32u) + t] = 0u;
    barrier();
    if (c == kCandidate) candidates[sFirst + rank] = place;
}
