#pragma once
// spatter-bench render: the GPU cost of the decal pass against decal count, visible fraction, screen
// coverage per decal, resolution and each feature of the decal shader.

namespace spatter::bench {

int runRenderCommand(int argc, char** argv);

} // namespace spatter::bench
