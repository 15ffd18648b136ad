#include "GalleryOptions.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace spatter::gallery {

const char* const kGalleryUsage = R"(usage: spatter-gallery [options]

The shooting gallery: shots land where aimed, decals sit on the detailed surface, follow moving
targets, wrap corners, never bleed onto the wall behind, and old decals give way per area.

With a display it opens a window (first-person controls below); without one, or with --headless,
it runs a scripted, seeded session and writes DIR/gallery.png and DIR/gallery.json.

options:
  --scene FILE        a .gltf, .glb, .obj, .ply, .off or .stl file (a glTF scene's dynamic nodes
                      are the targets, sliding on rails; in a scene with an animation its nodes
                      follow the first animation instead) or builtin:gallery (default; with a
                      skinned dummy whose arms swing, generated like the rest)
  --headless          run the scripted session even when a display is present
  --out DIR           output folder of the headless run (default gallery-out)
  --shots N           shots of the headless run (default 160)
  --seed N            seed of the scripted shots and of the decal system (default 1)
  --size WxH          image or window size (default 960x540 headless, 1280x720 in a window)
  --tolerance T       proxy tolerance in % of each object's bounding diagonal (default 0.5)
  --cache DIR         proxy cache folder (default $XDG_CACHE_HOME/spatter or ~/.cache/spatter)
  --quit-after N      window: close after N frames
  --time T            the scene's first animation (glTF: animated nodes, skins, morph targets)
                      starts at T seconds (default 0) and plays looping, in the window and in the
                      headless session (which advances the clock by each shot's interval)
  --load FILE         load the decals saved in FILE (by --save or a quick-save) before the session
  --save FILE         headless: save the decals at the end of the run to FILE; window: the
                      quick-save file (default OUT/quick.save)
  -h, --help          this text

window controls:
  mouse               look (Tab frees the cursor for the HUD)
  W A S D, Q E        move, down/up; Shift runs
  left button         bullet hole (hold for automatic fire)
  right button        paint splat (large, wraps around corners)
  F                   scorch mark
  F5, F9              quick-save, quick-load the decals (the --save file)
  R                   rebuild the proxies at the HUD's tolerance (clears the decals)
  Esc                 quit
)";

static bool parseInt(const std::string& s, long long lo, long long hi, long long& out) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno != 0 || v < lo || v > hi) return false;
    out = v;
    return true;
}

Result<GalleryOptions> parseGalleryOptions(int argc, char** argv) {
    GalleryOptions o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](std::string& out) -> bool {
            if (i + 1 >= argc) return false;
            out = argv[++i];
            return true;
        };
        std::string v;
        long long n = 0;
        if (arg == "-h" || arg == "--help") {
            o.help = true;
        } else if (arg == "--headless") {
            o.headless = true;
        } else if (arg == "--scene") {
            if (!value(o.scene)) return fail("--scene needs a file");
        } else if (arg == "--out") {
            if (!value(o.outDir) || o.outDir.empty()) return fail("--out needs a folder");
        } else if (arg == "--shots") {
            if (!value(v) || !parseInt(v, 0, 1000000, n)) return fail("--shots needs a count in 0..1000000");
            o.shots = int(n);
        } else if (arg == "--seed") {
            if (!value(v) || !parseInt(v, 0, INT64_MAX, n))
                return fail("--seed needs a non-negative integer");
            o.seed = uint64_t(n);
        } else if (arg == "--size") {
            long long w = 0, h = 0;
            const size_t x = value(v) ? v.find('x') : std::string::npos;
            if (x == std::string::npos || !parseInt(v.substr(0, x), 16, 8192, w) ||
                !parseInt(v.substr(x + 1), 16, 8192, h))
                return fail("--size needs WxH with each side in 16..8192");
            o.width = int(w);
            o.height = int(h);
        } else if (arg == "--tolerance") {
            char* end = nullptr;
            if (!value(v)) return fail("--tolerance needs a percentage");
            if (!v.empty() && v.back() == '%') v.pop_back();
            const float t = std::strtof(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !std::isfinite(t) || t < 0.0f || t > 50.0f)
                return fail("--tolerance needs a percentage in 0..50");
            o.tolerancePercent = t;
        } else if (arg == "--cache") {
            if (!value(o.cacheDir)) return fail("--cache needs a folder");
        } else if (arg == "--load") {
            if (!value(o.loadPath) || o.loadPath.empty()) return fail("--load needs a file");
        } else if (arg == "--save") {
            if (!value(o.savePath) || o.savePath.empty()) return fail("--save needs a file");
        } else if (arg == "--time") {
            char* end = nullptr;
            if (!value(v)) return fail("--time needs a number of seconds");
            const double t = std::strtod(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !std::isfinite(t))
                return fail("--time needs a finite number of seconds");
            o.startTime = t;
        } else if (arg == "--quit-after") {
            if (!value(v) || !parseInt(v, 1, 100000000, n)) return fail("--quit-after needs a frame count");
            o.quitAfterFrames = int(n);
        } else {
            return fail("unknown option '" + arg + "' (see --help)");
        }
    }
    return o;
}

} // namespace spatter::gallery
