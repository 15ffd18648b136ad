// GPU culling, the first pass (GpuCulling) where the test by place takes the groups listed: one
// invocation per group of 256 places of the draw order. A group out of view is culled whole
// (cull_group_test.glsl); every other group with a decal is listed for the test by place (cull.comp).
// It clears each group's visible count, and each block's, for the passes after it.
#include "projector.glsl"
#include "cull_layout.glsl"
#include "cull_group_bounds.glsl"
#include "cull_group_test.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_groups;

shared uint sListed, sFirst;

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
