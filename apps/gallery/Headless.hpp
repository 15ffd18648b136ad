#pragma once
// The scripted, seeded gallery session without a window: shots over the gallery and at the moving
// targets, frames of motion, then gallery.png and gallery.json in the output folder.

#include "GalleryOptions.hpp"

namespace spatter::gallery {

// Returns the process exit code; prints what it wrote, or the error, to stdout/stderr.
int runHeadless(const GalleryOptions& options);

} // namespace spatter::gallery
