// GPU culling, the first pass (GpuCulling): one invocation per group of 256 places of the draw order.
// A group whose decals, all drawable by the projector, lie on at most kGroupBoxes objects is culled
// whole when each of its boxes (GroupBounds) lies outside one of the view's side planes, with margins
// for rounding, or its object collapsed; every other group with a decal is listed for the test by
// place (cull.comp). It clears each group's visible count, and each block's, for the passes after it.
#include "projector.glsl"
#include "cull_layout.glsl"
#include "cull_group_bounds.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_groups;

shared uint sListed, sFirst;

// Whether box `g`, in its object's space, lies wholly outside one of the view's four side
// planes: its centre relative to the eye and the half extents of a box around its image there.
bool boxOutside(GroupBox g, ProjectorObject o) {
    vec4 c = vec4((o.model * vec4(g.center, 1.0)).xyz, 1.0);
    mat3 m = mat3(o.model);
    vec3 extent = mat3(abs(m[0]), abs(m[1]), abs(m[2])) * g.extent;
    vec4 w = vec4(u_viewProj[0][3], u_viewProj[1][3], u_viewProj[2][3], u_viewProj[3][3]);
    for (int k = 0; k < 4; ++k) {
        int row = k / 2;
        vec4 axis = vec4(u_viewProj[0][row], u_viewProj[1][row], u_viewProj[2][row], u_viewProj[3][row]);
        vec4 plane = (k & 1) == 0 ? w + axis : w - axis; // inside: dot(plane, c) >= 0
        float reach = dot(abs(plane.xyz), extent);
        float slack = reach * 1e-3 + 1e-5 * (dot(abs(plane), abs(c)) + reach);
        if (dot(plane, c) + reach < -slack) return true;
    }
    return false;
}

// Whether the group's places need the test by place.
bool byPlace(uint group) {
    for (uint k = 0u; k < kGroupBoxes; ++k) {
        GroupBox g = groupBoxes[group * kGroupBoxes + k];
        if (g.state == kBoxByPlace) return true;
        if (g.state != kBoxUsed) continue;
        if (!(float(g.object) < u_params.y)) return true;
        ProjectorObject o = objects[g.object];
        if (o.info.w != 0u) return true; // the host draws its decals: counted by place
        if (o.info.z == 0u && !boxOutside(g, o)) return true;
    }
    return false;
}

void main() {
    uint t = gl_LocalInvocationIndex, group = gl_GlobalInvocationID.x;
    if (t == 0u) sListed = 0u;
    barrier();
    bool listed = group < u_groups && byPlace(group);
    uint rank = listed ? atomicAdd(sListed, 1u) : 0u;
    if (group < u_groups) {
        groupData[group] = 0u;
        if (group % kBlockGroups == 0u) groupData[u_groups + group / kBlockGroups] = 0u;
    }
    barrier();
    if (t == 0u && sListed != 0u) sFirst = atomicAdd(tested.groupsX, sListed);
    barrier();
    if (listed) groupData[listStart(u_groups) + sFirst + rank] = group;
}
