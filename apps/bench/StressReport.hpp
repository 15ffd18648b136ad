#pragma once
// `spatter-bench stress`: runs the numerical stress cases (apps/bench/stress) at full size and prints
// a report table: case, what is measured, the largest error measured, its bound, and whether it
// holds. --json FILE writes every number.

namespace spatter::bench {

// argv[0] is "stress". Returns 0 when every case passes, 1 when one fails, 2 on
// bad options.
int runStressCommand(int argc, char** argv);

} // namespace spatter::bench
