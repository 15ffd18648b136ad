#include "spatter/render/GlContext.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <GLFW/glfw3.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

namespace spatter {

namespace {

bool debugWanted(DebugOutput d) {
#ifdef NDEBUG
    return d == DebugOutput::On;
#else
    return d != DebugOutput::Off;
#endif
}

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

std::string eglErrorText(EGLint error) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04x", unsigned(error));
    return buf;
}

// GLFW reports errors through a callback; the last message is kept for the Result.
std::mutex gGlfwMutex;
int gGlfwWindows = 0;
std::string gGlfwError;

void glfwErrorCallback(int code, const char* description) {
    gGlfwError = "GLFW error " + std::to_string(code) + ": " + (description ? description : "");
}

// What a context needs besides its handles: the driver strings and the debug-message counter.
struct ContextState {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE; // a 1x1 pbuffer where surfaceless make-current is missing
    GLFWwindow* window = nullptr;
    ContextInfo info;
    std::atomic<size_t> debugErrors{0};

    ContextState() = default;
    ContextState(const ContextState&) = delete;
    ContextState& operator=(const ContextState&) = delete;
    ~ContextState() {
        if (context != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == context)
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
            if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
            // The display is not terminated: EGL displays are shared by every context of the process.
        }
        if (window) {
            std::lock_guard<std::mutex> lock(gGlfwMutex);
            glfwDestroyWindow(window);
            if (--gGlfwWindows == 0) glfwTerminate();
        }
    }
};

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                              const GLchar* message, const void* user) {
    (void)source;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION || severity == GL_DEBUG_SEVERITY_LOW) return;
    auto* counter = static_cast<std::atomic<size_t>*>(const_cast<void*>(user));
    if (type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR) ++*counter;
    std::fprintf(stderr, "spatter GL debug [%s, id %u]: %s\n",
                 severity == GL_DEBUG_SEVERITY_HIGH ? "high" : "medium", id, message ? message : "");
}

// Checks the version and installs the debug callback on the current context.
Status finishContext(ContextState& impl, bool debug) {
    if (epoxy_gl_version() < 45 || epoxy_is_desktop_gl() == 0)
        return fail("the context is OpenGL " + glString(GL_VERSION) + ", 4.5 core is required");
    impl.info.renderer = glString(GL_RENDERER);
    impl.info.vendor = glString(GL_VENDOR);
    impl.info.version = glString(GL_VERSION);
    if (debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, &impl.debugErrors);
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr,
                              GL_FALSE);
    }
    return {};
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

// Tries to create and make current a 4.5 core context on `display`. Returns an empty string on
// success, else the reason.
std::string tryDisplay(ContextState& impl, EGLDisplay display, bool debug) {
    if (display == EGL_NO_DISPLAY) return "no display";
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor))
        return "eglInitialize failed (" + eglErrorText(eglGetError()) + ")";
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(EGL_OPENGL_API) failed";

    const bool surfaceless = hasExtension(ext, "EGL_KHR_surfaceless_context");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!surfaceless || !hasExtension(ext, "EGL_KHR_no_config_context")) {
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                  EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display, attribs, &config, 1, &count) || count < 1)
            return "no OpenGL EGL config";
    }
    std::vector<EGLint> attribs = {
        EGL_CONTEXT_MAJOR_VERSION_KHR,       4,
        EGL_CONTEXT_MINOR_VERSION_KHR,       5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
    if (debug) attribs.insert(attribs.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
    attribs.push_back(EGL_NONE);
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
    if (context == EGL_NO_CONTEXT) return "no OpenGL 4.5 core context (" + eglErrorText(eglGetError()) + ")";
    EGLSurface surface = EGL_NO_SURFACE;
    if (!surfaceless) {
        const EGLint pbuffer[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surface = eglCreatePbufferSurface(display, config, pbuffer);
        if (surface == EGL_NO_SURFACE) {
            eglDestroyContext(display, context);
            return "no pbuffer surface (" + eglErrorText(eglGetError()) + ")";
        }
    }
    if (!eglMakeCurrent(display, surface, surface, context)) {
        const EGLint error = eglGetError();
        eglDestroyContext(display, context);
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        return "eglMakeCurrent failed (" + eglErrorText(error) + ")";
    }
    impl.display = display;
    impl.context = context;
    impl.surface = surface;
    if (Status s = finishContext(impl, debug); !s) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        impl.display = EGL_NO_DISPLAY;
        impl.context = EGL_NO_CONTEXT;
        impl.surface = EGL_NO_SURFACE;
        return s.error();
    }
    return {};
}

} // namespace

struct GlContext::Impl : ContextState {};

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GlContext::GlContext(GlContext&&) noexcept = default;
GlContext& GlContext::operator=(GlContext&&) noexcept = default;
GlContext::~GlContext() = default;

Result<GlContext> GlContext::createHeadless(const HeadlessSettings& settings) {
    if (!epoxy_has_egl()) return fail("headless GL: libEGL could not be loaded");
    const bool debug = debugWanted(settings.debug);
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto impl = std::make_unique<Impl>();
    std::string tried;
    auto note = [&](const std::string& what, const std::string& why) {
        tried += (tried.empty() ? "" : "; ") + what + ": " + why;
    };

    // Devices of the device platform, hardware first.
    std::vector<EGLDeviceEXT> hardware, software;
    if (hasExtension(client, "EGL_EXT_device_enumeration") &&
        hasExtension(client, "EGL_EXT_platform_device")) {
        EGLint count = 0;
        if (eglQueryDevicesEXT(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
            if (eglQueryDevicesEXT(count, devices.data(), &count)) {
                devices.resize(size_t(count));
                for (EGLDeviceEXT d : devices) {
                    const char* dext = eglQueryDeviceStringEXT(d, EGL_EXTENSIONS);
                    (hasExtension(dext, "EGL_MESA_device_software") ? software : hardware).push_back(d);
                }
            }
        }
    } else {
        note("device platform", "EGL_EXT_platform_device is not available");
    }
    auto tryDevices = [&](const std::vector<EGLDeviceEXT>& devices, const char* platform) {
        for (size_t i = 0; i < devices.size(); ++i) {
            EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            const std::string why = tryDisplay(*impl, display, debug);
            if (why.empty()) {
                impl->info.platform = platform;
                return true;
            }
            note(std::string(platform) + " " + std::to_string(i), why);
        }
        return false;
    };
    auto trySurfaceless = [&]() {
        if (!hasExtension(client, "EGL_MESA_platform_surfaceless")) {
            note("surfaceless platform", "EGL_MESA_platform_surfaceless is not available");
            return false;
        }
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        const std::string why = tryDisplay(*impl, display, debug);
        if (why.empty()) {
            impl->info.platform = "egl-surfaceless";
            return true;
        }
        note("surfaceless platform", why);
        return false;
    };

    bool ok = false;
    switch (settings.platform) {
    case HeadlessPlatform::Device:
        ok = tryDevices(hardware, "egl-device") || tryDevices(software, "egl-device-software");
        break;
    case HeadlessPlatform::Surfaceless:
        ok = trySurfaceless();
        break;
    case HeadlessPlatform::Auto:
        ok = tryDevices(hardware, "egl-device") || trySurfaceless() ||
             tryDevices(software, "egl-device-software");
        break;
    }
    if (!ok)
        return fail("headless GL: no OpenGL 4.5 core context (" + (tried.empty() ? "no EGL device" : tried) +
                    ")");
    return GlContext(std::move(impl));
}

Result<GlContext> GlContext::createWindow(const WindowSettings& settings) {
    if (settings.width <= 0 || settings.height <= 0 || settings.width > 16384 || settings.height > 16384)
        return fail("window: size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                    " is out of range");
    const bool debug = debugWanted(settings.debug);
    auto impl = std::make_unique<Impl>();
    {
        std::lock_guard<std::mutex> lock(gGlfwMutex);
        glfwSetErrorCallback(glfwErrorCallback);
        gGlfwError.clear();
        if (gGlfwWindows == 0 && !glfwInit()) return fail("window: glfwInit failed (" + gGlfwError + ")");
        glfwDefaultWindowHints();
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
        glfwWindowHint(GLFW_RESIZABLE, settings.resizable ? GLFW_TRUE : GLFW_FALSE);
        glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_TRUE);
        impl->window =
            glfwCreateWindow(settings.width, settings.height, settings.title.c_str(), nullptr, nullptr);
        if (!impl->window) {
            if (gGlfwWindows == 0) glfwTerminate();
            return fail("window: no OpenGL 4.5 core window (" + gGlfwError + ")");
        }
        ++gGlfwWindows;
    }
    glfwMakeContextCurrent(impl->window);
    glfwSwapInterval(settings.vsync ? 1 : 0);
    if (Status s = finishContext(*impl, debug); !s) return fail("window: " + s.error());
    impl->info.platform = "glfw";
    return GlContext(std::move(impl));
}

Status GlContext::makeCurrent() const {
    if (impl_->window) {
        glfwMakeContextCurrent(impl_->window);
        return {};
    }
    if (!eglBindAPI(EGL_OPENGL_API) ||
        !eglMakeCurrent(impl_->display, impl_->surface, impl_->surface, impl_->context))
        return fail("eglMakeCurrent failed (" + eglErrorText(eglGetError()) + ")");
    return {};
}

const ContextInfo& GlContext::info() const {
    return impl_->info;
}
bool GlContext::headless() const {
    return impl_->window == nullptr;
}
GLFWwindow* GlContext::window() const {
    return impl_->window;
}
bool GlContext::shouldClose() const {
    return impl_->window ? glfwWindowShouldClose(impl_->window) != 0 : true;
}

void GlContext::swapBuffers() const {
    if (impl_->window) glfwSwapBuffers(impl_->window);
}

void GlContext::pollEvents() const {
    if (impl_->window) glfwPollEvents();
}

void GlContext::framebufferSize(int& width, int& height) const {
    width = height = 0;
    if (impl_->window) glfwGetFramebufferSize(impl_->window, &width, &height);
}

size_t GlContext::debugErrorCount() const {
    return impl_->debugErrors.load();
}

} // namespace spatter
