#pragma once
// The files a headless gallery run writes, made ready before the session: so that a run fails at
// once, not after its shots, on an output it cannot write.

#include "GalleryOptions.hpp"

#include "spatter/core/Result.hpp"

namespace spatter::gallery {

// Creates the --out folder; then fails, naming the option and the path, unless DIR/gallery.png,
// DIR/gallery.json and the --save file can be written, none of them is the scene or another of
// them, and the --cache folder (when given) is usable.
Status prepareHeadlessOutputs(const GalleryOptions& options);

} // namespace spatter::gallery
