// The buffers the GPU culling passes share (GpuCulling; cull_groups.comp, cull.comp, cull_exact.comp,
// cull_scatter.comp). A place is an entry of the draw order; a group, 256 consecutive places.

layout(std430, binding = 2) coherent buffer GroupData {
    // [0, groups): the visible places of each group; from groups on, the visible places of each block
    // of kBlockGroups groups, so that a group's first place in the visible list sums at most a block's
    // groups and the blocks before it, not every group before it; from listStart() on, the groups
    // whose places are tested one by one (cull_groups.comp lists them, testedGroups of them)
    uint groupData[];
};

struct DrawElementsIndirect {
    uint count, instanceCount, firstIndex, baseVertex, baseInstance;
};

struct DispatchIndirect {
    uint groupsX, groupsY, groupsZ;
};

layout(std430, binding = 5) coherent buffer Counters {
    DrawElementsIndirect draw; // the cube's 36 indices, the visible decals as instances
    uint occludedCount;        // boxes in the frustum that the occlusion test culled
    uint invalidCount;         // decals that cannot be drawn: their box, type or object
    uint hostDrawnCount;       // decals of a type or on an object the host draws itself
    uint candidateCount;       // places cull.comp left to cull_exact.comp
    DispatchIndirect tested;   // x: the groups cull_groups.comp left to cull.comp, a work group each
                               // (cull.comp testing every group: the groups it culled whole)
};

layout(std430, binding = 6) readonly buffer DrawOrder {
    uint drawOrder[]; // decal indices; 0xffffffff: an empty place
};

const uint kGroupPlaces = 256u;
const uint kBlockGroups = 256u;

// Where the list of the groups tested by place starts in groupData, for `groups` groups.
uint listStart(uint groups) {
    return groups + (groups + kBlockGroups - 1u) / kBlockGroups;
}
