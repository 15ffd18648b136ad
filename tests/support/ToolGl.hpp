#pragma once
// Whether the tools the tests run as processes can get a headless GL context here, and the guard
// that skips a test when they cannot (and fails it under CI=true).

#include "TestData.hpp"

#include "spatter/render/GlContext.hpp"

#include <string>

namespace spatter::test {

// Why the tools cannot render here (no headless GL context), or an empty string.
inline std::string noToolGl() {
    static const std::string why = [] {
        Result<GlContext> gl = GlContext::createHeadless();
        return gl.ok() ? std::string() : gl.error();
    }();
    return why;
}

} // namespace spatter::test

// Skips the test when no headless GL context can be made, except under CI=true, where that fails.
#define SPATTER_REQUIRE_TOOL_GL()                                                                            \
    if (!::spatter::test::noToolGl().empty()) {                                                              \
        if (::spatter::test::runningInCi())                                                                  \
            FAIL() << "CI=true but no headless GL context: " << ::spatter::test::noToolGl();                 \
        GTEST_SKIP() << "no headless OpenGL 4.5 context (" << ::spatter::test::noToolGl() << ")";            \
    }
