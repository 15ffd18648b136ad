#pragma once
// spatter-bench proxy: certified proxies against plain meshoptimizer. For each mesh and tolerance, the
// anchor is the fewest triangles meshopt_simplify (LockBorder) reaches with a two-sided Hausdorff
// distance within the tolerance measured by dense sampling, its target error found by bisection; the
// builder's proxy is compared with it in triangles and in wall time, in the same run.

namespace spatter::bench {

int runProxyCommand(int argc, char** argv);

} // namespace spatter::bench
