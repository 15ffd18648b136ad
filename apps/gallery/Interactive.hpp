#pragma once
// The gallery in a window: first-person camera, shooting with the mouse, the HUD.

#include "GalleryOptions.hpp"

#include "spatter/render/GlContext.hpp"

namespace spatter::gallery {

// Runs until the window closes (Esc, or options.quitAfterFrames). Returns the process exit code.
int runInteractive(const GalleryOptions& options, GlContext& context);

} // namespace spatter::gallery
