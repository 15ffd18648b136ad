#pragma once
// spatter-bench volumetric: what volumetric decals cost against flat ones, in one run.

namespace spatter::bench {

int runVolumetricCommand(int argc, char** argv);

} // namespace spatter::bench
