#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/render/GlContext.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

using namespace spatter;

TEST(GlContext, HeadlessContextReportsDriverAndPlatform) {
    SPATTER_REQUIRE_GL(gl);
    EXPECT_TRUE(gl.headless());
    EXPECT_FALSE(gl.info().renderer.empty());
    EXPECT_FALSE(gl.info().vendor.empty());
    EXPECT_NE(gl.info().version.find("4."), std::string::npos) << gl.info().version;
    EXPECT_TRUE(gl.info().platform == "egl-device" || gl.info().platform == "egl-surfaceless" ||
                gl.info().platform == "egl-device-software")
        << gl.info().platform;
    EXPECT_EQ(gl.window(), nullptr);
    EXPECT_TRUE(gl.shouldClose());
    EXPECT_TRUE(gl.makeCurrent().ok());
}

TEST(GlContext, WindowWithoutDisplayIsAnErrorNotACrash) {
    if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) GTEST_SKIP() << "a display is available";
    Result<GlContext> window = GlContext::createWindow({320, 200, "test"});
    ASSERT_FALSE(window.ok());
    EXPECT_NE(window.error().find("window"), std::string::npos) << window.error();
}

TEST(GlContext, RejectsWindowSizeOutOfRange) {
    WindowSettings s;
    s.width = 0;
    Result<GlContext> window = GlContext::createWindow(s);
    ASSERT_FALSE(window.ok());
    EXPECT_NE(window.error().find("out of range"), std::string::npos) << window.error();
}

TEST(GlContext, HeadlessPlatformCanBeChosen) {
    SPATTER_REQUIRE_GL(gl);
    for (HeadlessPlatform platform : {HeadlessPlatform::Surfaceless, HeadlessPlatform::Device}) {
        HeadlessSettings s;
        s.platform = platform;
        Result<GlContext> c = GlContext::createHeadless(s);
        if (!c.ok()) {
            // Not every machine has both platforms; the error must say what was tried.
            EXPECT_NE(c.error().find("headless GL"), std::string::npos) << c.error();
            continue;
        }
        const std::string expected =
            platform == HeadlessPlatform::Surfaceless ? "egl-surfaceless" : "egl-device";
        EXPECT_EQ(c->info().platform.rfind(expected, 0), 0u) << c->info().platform;
        EXPECT_FALSE(c->info().renderer.empty());
    }
    ASSERT_TRUE(gl.makeCurrent().ok()); // the shared context again, for the tests that follow
}
