#pragma once
// What a path named on a command line must be, checked before a tool does its work: a file it can
// read, a file it can create, a folder it can keep files in, a program it can run. The errors name
// the option and the path ("--rays: data is a directory, not a file").

#include "spatter/core/Result.hpp"

#include <string>

namespace spatter::cli {

// A path and what named it: an option ("--out") or, for an operand, its name in the usage ("SCENE").
struct NamedPath {
    std::string option;
    std::string path;
};

// Fails unless `p` is an existing file (not a directory) that this process may read.
Status readableFile(const NamedPath& p);

// Fails unless this process can write `p`: an existing file (not a directory) it may write, or a new
// name in an existing folder it may write into.
Status creatableFile(const NamedPath& p);

// Fails unless `p` is a folder this process may write into, or one it can create: the nearest of its
// ancestors that exists is a folder it may write into.
Status usableDirectory(const NamedPath& p);

// Fails unless `p` is a regular file this process may execute.
Status executableFile(const NamedPath& p);

} // namespace spatter::cli
