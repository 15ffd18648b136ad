#pragma once
// spatter-bench placement: the cost of spawning a decal against tracing the same ray with raw
// Embree, on the same proxy and rays, in one run (Google Benchmark, repetitions interleaved).

namespace spatter::bench {

int runPlacementCommand(int argc, char** argv);

} // namespace spatter::bench
