// spatter-gallery: the shooting-gallery demo (see --help).

#include "GalleryOptions.hpp"
#include "GalleryOutputs.hpp"
#include "Headless.hpp"
#include "Interactive.hpp"

#include <cstdio>
#include <cstdlib>
#include <iostream>

using namespace spatter;
using namespace spatter::gallery;

static bool displayPresent() {
    const char* x = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (wayland && *wayland);
}

// The headless session, once its outputs are ready (exit code 2 when they cannot be).
static int headless(const GalleryOptions& options) {
    if (Status s = prepareHeadlessOutputs(options); !s) {
        std::cerr << "spatter-gallery: " << s.error() << "\n";
        return 2;
    }
    return runHeadless(options);
}

int main(int argc, char** argv) {
    Result<GalleryOptions> options = parseGalleryOptions(argc, argv);
    if (!options) {
        std::cerr << "spatter-gallery: " << options.error() << "\n";
        return 2;
    }
    if (options->help) {
        std::fputs(kGalleryUsage, stdout);
        return 0;
    }
    if (options->headless || !displayPresent()) return headless(options.value());

    WindowSettings window;
    window.title = "spatter shooting gallery";
    if (options->width) {
        window.width = options->width;
        window.height = options->height;
    }
    Result<GlContext> context = GlContext::createWindow(window);
    if (!context) {
        std::cerr << "spatter-gallery: no window (" << context.error() << "); running headless\n";
        return headless(options.value());
    }
    return runInteractive(options.value(), context.value());
}
