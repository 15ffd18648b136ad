#pragma once
// Running the command-line tools as separate processes, for the tool tests.

#include "TestData.hpp"
#include "spatter/render/GlContext.hpp"

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

// Why the tools cannot render here (no headless GL context), or an empty string.
inline std::string noGl() {
    static const std::string why = [] {
        Result<GlContext> gl = GlContext::createHeadless();
        return gl.ok() ? std::string() : gl.error();
    }();
    return why;
}

} // namespace spatter::test

// Skips the calling test when the tools cannot get a headless GL context here (fails under CI=true).
#define SPATTER_REQUIRE_TOOL_GL()                                                                            \
    if (!::spatter::test::noGl().empty()) {                                                                  \
        if (::spatter::test::runningInCi())                                                                  \
            FAIL() << "CI=true but no headless GL context: " << ::spatter::test::noGl();                     \
        GTEST_SKIP() << "no headless OpenGL 4.5 context (" << ::spatter::test::noGl() << ")";                \
    }
