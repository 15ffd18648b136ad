#pragma once
// spatter-bench skip: every skip of the design measured on against forced off, in one run.

namespace spatter::bench {

int runSkipCommand(int argc, char** argv);

} // namespace spatter::bench
