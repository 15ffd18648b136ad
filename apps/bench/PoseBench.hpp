#pragma once
// spatter-bench pose: the CPU cost of posing an animated scene per frame (SceneEvaluator: node
// transforms, joint matrices, morph weights), and of the posed positions of its deforming meshes.

namespace spatter::bench {

int runPoseCommand(int argc, char** argv);

} // namespace spatter::bench
