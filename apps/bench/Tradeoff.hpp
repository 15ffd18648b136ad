#pragma once
// spatter-bench tradeoff: what each proxy setting costs (build, BVH, placement time) and what it buys
// (distance to the render surface, hit/miss agreement, decal coverage), side by side with the render
// mesh itself and the three.js decal workflow (bench/peers/threejs) on the same mesh and rays.

namespace spatter::bench {

int runTradeoffCommand(int argc, char** argv);

} // namespace spatter::bench
