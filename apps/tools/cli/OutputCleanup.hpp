#pragma once
// The files a run has begun to write, removed when the run fails, so that a failed run leaves no
// output behind, whole or half-written.

#include <string>
#include <vector>

namespace spatter::cli {

class OutputCleanup {
public:
    OutputCleanup() = default;
    OutputCleanup(const OutputCleanup&) = delete;
    OutputCleanup& operator=(const OutputCleanup&) = delete;
    // Removes every path given to writing() since the last keep() that is a regular file (a device
    // such as /dev/null, or a symbolic link, stays).
    ~OutputCleanup();

    // The run is about to write `path`.
    void writing(const std::string& path) { paths_.push_back(path); }
    // The run succeeded: the files written stay.
    void keep() { paths_.clear(); }

private:
    std::vector<std::string> paths_;
};

} // namespace spatter::cli
