#pragma once
// Command-line options of the shooting-gallery demo.

#include "spatter/core/Result.hpp"

#include <cstdint>
#include <string>

namespace spatter::gallery {

struct GalleryOptions {
    std::string scene = "builtin:gallery";
    bool headless = false; // forced headless; also chosen when no display can be opened
    std::string outDir = "gallery-out";
    int shots = 160; // headless: scripted shots
    uint64_t seed = 1;
    int width = 0; // 0: 1280x720 in a window, 960x540 headless
    int height = 0;
    float tolerancePercent = 0.5f; // proxy tolerance, % of each object's bounding diagonal
    std::string cacheDir;          // proxy cache; empty: $XDG_CACHE_HOME/spatter or ~/.cache/spatter
    int quitAfterFrames = 0;       // window: close after this many frames (0: run until closed)
    double startTime = 0.0;        // where the scene's first animation starts, seconds (--time)
    std::string loadPath;          // decal state to load at the start (DecalPersistence.hpp); empty: none
    std::string savePath;          // headless: where the final decal state goes; window: the quick-save
                                   // file (empty: OUT/quick.save)
    bool help = false;
};

// Parses argv. Errors name the option and the bad value.
Result<GalleryOptions> parseGalleryOptions(int argc, char** argv);

extern const char* const kGalleryUsage;

} // namespace spatter::gallery
