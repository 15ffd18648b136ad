#include "cli/Tolerance.hpp"

#include "spatter/core/TextFields.hpp"

#include <cmath>
#include <limits>

namespace spatter::cli {

bool parseTolerance(const std::string& text, ProxySettings& settings) {
    const bool relative = !text.empty() && text.back() == '%';
    double t = 0.0;
    if (!parseDecimal(relative ? text.substr(0, text.size() - 1) : text, t) || !(t >= 0.0)) return false;
    const double tolerance = relative ? t / 100.0 : t;
    if (tolerance > double(std::numeric_limits<float>::max())) return false;
    settings.tolerance = float(tolerance);
    settings.toleranceRelative = relative;
    return true;
}

} // namespace spatter::cli
