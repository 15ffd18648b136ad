#pragma once
// RegularFile: whether a path a loader is about to read names a regular file. Opening a FIFO waits for
// a writer that may never come, and a directory or a device has no length to read, so the loaders
// read regular files only (symbolic links followed) and say what the path is otherwise.

#include <string>

namespace spatter::detail {

// Empty when `path` is a regular file; otherwise what it is, for a message after the path: "file not
// found", "is a directory", "is a FIFO (named pipe), not a regular file" and so on.
std::string regularFileProblem(const std::string& path);

} // namespace spatter::detail
