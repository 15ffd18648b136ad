#pragma once
// GlContext: an OpenGL 4.5 core profile context, made current on the creating thread. Either
// headless through EGL (no display, no default framebuffer: the renderer draws into framebuffer
// objects) or in a GLFW window. libepoxy resolves every GL entry point, so users need no loader.
//
//   Result<GlContext> gl = GlContext::createHeadless();   // tests, tools, benchmarks
//   Result<GlContext> gl = GlContext::createWindow({1280, 720, "spatter"});   // the demo
//
// Headless platforms, in the order tried by HeadlessPlatform::Auto:
//   1. EGL's device platform (EGL_EXT_platform_device): hardware devices first, so a GPU machine
//      renders on its GPU (NVIDIA's GL);
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): llvmpipe on a machine without a
//      GPU or display;
//   3. software devices of the device platform (Mesa's EGL_MESA_device_software).
// When no platform gives a 4.5 core context the result is an error naming what was tried; nothing
// aborts. The context stays current on the creating thread; GL calls from other threads are not
// supported.

#include "spatter/core/Result.hpp"

#include <cstddef>
#include <memory>
#include <string>

struct GLFWwindow;

namespace spatter {

enum class HeadlessPlatform { Auto, Device, Surfaceless };

// KHR_debug output: Default is on in debug builds of the library (NDEBUG not defined) and off in
// release builds. When on, the context is a debug context and messages of high and medium severity
// go to stderr and are counted (GlContext::debugErrorCount).
enum class DebugOutput { Default, On, Off };

struct HeadlessSettings {
    HeadlessPlatform platform = HeadlessPlatform::Auto;
    DebugOutput debug = DebugOutput::Default;
};

struct WindowSettings {
    int width = 1280;
    int height = 720;
    std::string title = "spatter";
    bool vsync = true;
    bool resizable = true;
    DebugOutput debug = DebugOutput::Default;
};

// What the driver reports, for logs and frame stats.
struct ContextInfo {
    std::string renderer; // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string vendor;   // GL_VENDOR
    std::string version;  // GL_VERSION
    std::string platform; // "egl-device", "egl-surfaceless", "egl-device-software" or "glfw"
};

class GlContext {
public:
    // A headless 4.5 core context through EGL (see above for the order of platforms).
    static Result<GlContext> createHeadless(const HeadlessSettings& settings = {});
    // A window with a 4.5 core context. Fails with GLFW's message when there is no display.
    static Result<GlContext> createWindow(const WindowSettings& settings = {});

    GlContext(GlContext&&) noexcept;
    GlContext& operator=(GlContext&&) noexcept;
    // Destroys the context (and the window). Everything created with it must be destroyed first.
    ~GlContext();

    // Makes the context current on the calling thread again.
    Status makeCurrent() const;
    const ContextInfo& info() const;
    bool headless() const;

    // Window only (headless: nullptr, true, no-op, 0 x 0).
    GLFWwindow* window() const;
    bool shouldClose() const;
    void swapBuffers() const;
    void pollEvents() const;
    void framebufferSize(int& width, int& height) const;

    // High- and medium-severity debug messages received so far (0 when debug output is off).
    size_t debugErrorCount() const;

private:
    struct Impl;
    explicit GlContext(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter
