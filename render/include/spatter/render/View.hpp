#pragma once
// View: what the renderer writes into its output image.

#include "spatter/core/Result.hpp"

#include <string>

namespace spatter {

enum class View {
    Final,    // lit, tone-mapped, sRGB
    Albedo,   // G-buffer base colour after the decal pass, sRGB
    Normal,   // G-buffer world normal after the decal pass, n * 0.5 + 0.5 (raw bytes, not sRGB)
    Depth,    // distance from the eye: white at the nearest scene point, black at the farthest and
              // for the background
    Ids,      // 8-bit object decal IDs as colours (ID 0, static geometry, dark grey; background black)
    Coverage, // white where at least one decal writes the pixel (inside its box, ID matching,
              // within its max angle, inside its wrapped footprint), a volumetric decal's crater
              // shows or a texture-space decal's layer shows, black elsewhere
};

// "final", "albedo", "normal", "depth", "ids", "coverage".
const char* toString(View view);
// The view named `name` (as toString writes it), or an error listing the names.
Result<View> parseView(const std::string& name);

} // namespace spatter
