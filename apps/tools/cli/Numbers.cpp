#include "cli/Numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace spatter::cli {

namespace {

// Moves `i` past the decimal digits of `s` from `i`; returns how many there were.
size_t skipDigits(const std::string& s, size_t& i) {
    const size_t start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9')
        ++i;
    return i - start;
}

// [+-] digits [. digits] [(e|E) [+-] digits], with at least one digit before the exponent.
bool decimalSyntax(const std::string& s) {
    size_t i = 0;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
    size_t digits = skipDigits(s, i);
    if (i < s.size() && s[i] == '.') digits += skipDigits(s, ++i);
    if (digits == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
        if (skipDigits(s, i) == 0) return false;
    }
    return i == s.size();
}

} // namespace

bool parseDecimal(const std::string& text, double& out) {
    if (!decimalSyntax(text)) return false;
    const double v = std::strtod(text.c_str(), nullptr); // the tools keep the "C" locale
    if (!std::isfinite(v)) return false;                 // beyond double's range
    out = v;
    return true;
}

bool parseWhole(const std::string& text, uint64_t max, uint64_t& out) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
    uint64_t v = 0;
    const std::from_chars_result r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || v > max) return false;
    out = v;
    return true;
}

} // namespace spatter::cli
