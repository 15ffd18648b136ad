#pragma once
// Running the command-line tools as separate processes, for the tool tests.

#include "ToolGl.hpp"

#include <cstdlib>
#include <string>
#include <sys/wait.h>

namespace spatter::test {

// Runs `exe` with `args`; returns its exit code (-1 when it did not exit normally).
inline int runExe(const std::string& exe, const std::string& args) {
    const std::string cmd = exe + " " + args + " >/dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Runs spatter-render with `args`.
inline int runTool(const std::string& args) {
    return runExe(SPATTER_RENDER_TOOL, args);
}

} // namespace spatter::test
