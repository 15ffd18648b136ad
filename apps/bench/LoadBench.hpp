#pragma once
// spatter-bench load: the wall time of loading a Draco-compressed glTF against its uncompressed twin,
// measured in the same run.

namespace spatter::bench {

int runLoadCommand(int argc, char** argv);

} // namespace spatter::bench
