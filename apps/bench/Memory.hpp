#pragma once
// spatter-bench memory: bytes per decal on the CPU (decal system: records, area grid, handle slots;
// renderer: its instance copies) and on the GPU (instance data), and per object (proxy, collision
// BVH, texture-space decal texture), measured.

namespace spatter::bench {

int runMemoryCommand(int argc, char** argv);

} // namespace spatter::bench
