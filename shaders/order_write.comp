// The draw order's changes on the GPU (GpuCulling::updateDrawOrder) where the CPU keeps no copy of
// its entries: one invocation per write sets one entry (DrawOrder::Changes::writes, one per entry).
layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_count; // writes

layout(std430, binding = 0) readonly buffer Writes {
    uvec2 writes[]; // x: entry, y: its value (a decal index, or 0xffffffff: empty)
};
layout(std430, binding = 6) writeonly buffer DrawOrder {
    uint drawOrder[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    drawOrder[writes[i].x] = writes[i].y;
}
