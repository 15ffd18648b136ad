#include "GalleryOptions.hpp"

#include "cli/Arguments.hpp"
#include "cli/Numbers.hpp"
#include "spatter/core/TextFields.hpp"

#include <cstdint>
#include <optional>
#include <set>
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

Each option is given once, with its value (a following "--..." is not one); numbers are decimal,
N a whole number (no sign, blanks or hexadecimal). Before the session a headless run creates the
--out folder (so that --save OUT/NAME works) and checks that DIR/gallery.png, DIR/gallery.json and
the --save file can be written and are neither the scene nor each other, and that --cache is a
folder. Exit code 2 on bad options (these checks included), 1 when the session fails.

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

namespace {

// A whole number in lo..hi, digits only.
bool parseInt(const std::string& s, uint64_t lo, uint64_t hi, long long& out) {
    uint64_t v = 0;
    if (!cli::parseWhole(s, hi, v) || v < lo) return false;
    out = (long long)v;
    return true;
}

// Reads the value `v` of the option `arg` into `o`; an error message, or "" when it is one.
std::string parseValue(const std::string& arg, const std::string& v, GalleryOptions& o) {
    long long n = 0, w = 0, h = 0;
    double d = 0.0;
    if (arg == "--scene") {
        o.scene = v;
    } else if (arg == "--out") {
        if (v.empty()) return "--out needs a folder";
        o.outDir = v;
    } else if (arg == "--shots") {
        if (!parseInt(v, 0, 1000000, n)) return "--shots needs a count in 0..1000000";
        o.shots = int(n);
    } else if (arg == "--seed") {
        if (!parseInt(v, 0, INT64_MAX, n))
            return "--seed needs a whole number in 0.." + std::to_string(INT64_MAX);
        o.seed = uint64_t(n);
    } else if (arg == "--size") {
        const size_t x = v.find('x');
        if (x == std::string::npos || !parseInt(v.substr(0, x), 16, 8192, w) ||
            !parseInt(v.substr(x + 1), 16, 8192, h))
            return "--size needs WxH with each side in 16..8192";
        o.width = int(w);
        o.height = int(h);
    } else if (arg == "--tolerance") {
        const std::string t = !v.empty() && v.back() == '%' ? v.substr(0, v.size() - 1) : v;
        if (!parseDecimal(t, d) || d < 0.0 || d > 50.0) return "--tolerance needs a percentage in 0..50";
        o.tolerancePercent = float(d);
    } else if (arg == "--cache") {
        o.cacheDir = v;
    } else if (arg == "--load" || arg == "--save") {
        if (v.empty()) return arg + " needs a file";
        (arg == "--load" ? o.loadPath : o.savePath) = v;
    } else if (arg == "--time") {
        if (!parseDecimal(v, d)) return "--time needs a finite number of seconds";
        o.startTime = d;
    } else if (arg == "--quit-after") {
        if (!parseInt(v, 1, 100000000, n)) return "--quit-after needs a frame count";
        o.quitAfterFrames = int(n);
    }
    return "";
}

} // namespace

Result<GalleryOptions> parseGalleryOptions(int argc, char** argv) {
    static const std::set<std::string> kValued = {"--scene", "--out",       "--shots",     "--seed",
                                                  "--size",  "--tolerance", "--cache",     "--load",
                                                  "--save",  "--time",      "--quit-after"};
    GalleryOptions o;
    cli::Arguments args(argc, argv);
    while (args.more()) {
        const Result<std::string> arg = args.next();
        if (!arg) return fail(arg.error());
        if (*arg == "-h" || *arg == "--help") {
            o.help = true;
        } else if (*arg == "--headless") {
            o.headless = true;
        } else if (kValued.count(*arg)) {
            const std::optional<std::string> v = args.value();
            if (!v) return fail(*arg + " needs a value");
            if (const std::string error = parseValue(*arg, *v, o); !error.empty()) return fail(error);
        } else {
            return fail("unknown option '" + *arg + "' (see --help)");
        }
    }
    return o;
}

} // namespace spatter::gallery
