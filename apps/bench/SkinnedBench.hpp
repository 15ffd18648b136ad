#pragma once
// spatter-bench skinned: decals on skinned objects. What posing a skinned object's collision mesh
// costs per frame (render mesh and deforming proxy), what a spawn on a posed skinned object costs
// against one on the same surface built static, how far decals drift from the skin point they were
// placed on over an animation cycle (the library's skin anchors against decals attached to the
// nearest joint, as engines attach them), and the deforming proxy's bound over the poses.

namespace spatter::bench {

int runSkinnedCommand(int argc, char** argv);

} // namespace spatter::bench
