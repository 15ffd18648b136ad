#pragma once
// A proxy tolerance on a command line (spatter-place --proxy TOL, spatter-proxy --tolerance T):
// absolute, "0.01" in world units, or relative, "1%" of each object's bounding diagonal.

#include "spatter/core/ProxyBuilder.hpp"

#include <string>

namespace spatter::cli {

// Sets settings.tolerance and settings.toleranceRelative from `text`: a decimal number >= 0 (see
// spatter::parseDecimal), then '%' for a relative one. False, leaving `settings` as it was, for anything else
// and for a tolerance beyond float's range.
bool parseTolerance(const std::string& text, ProxySettings& settings);

} // namespace spatter::cli
