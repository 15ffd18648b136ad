#pragma once
// Two paths of a command line that name one file: an output that would overwrite an input, or two
// outputs that would overwrite each other.

#include "cli/PathChecks.hpp"

#include "spatter/core/Result.hpp"

#include <string>
#include <vector>

namespace spatter::cli {

// Whether `a` and `b` name the same file: equivalent files where both exist, else the same path once
// made absolute and free of symbolic links, "." and "..".
bool sameFile(const std::string& a, const std::string& b);

// Fails when two of `outputs`, or an output and one of `inputs`, name the same file: "--out and --save
// name the same file (x.jsonl)". Empty paths and "-" (standard input or output) are left out.
Status distinctFiles(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

} // namespace spatter::cli
