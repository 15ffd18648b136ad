#include "spatter/core/TextFields.hpp"

#include <cmath>
#include <cstdlib>

namespace spatter {

std::string trimBlanks(const std::string& text) {
    const size_t a = text.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    const size_t b = text.find_last_not_of(" \t\r\n");
    return text.substr(a, b - a + 1);
}

std::vector<std::string> splitFields(const std::string& text, char sep) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : text) {
        if (c == sep) {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    parts.push_back(cur);
    return parts;
}

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
    const double v = std::strtod(text.c_str(), nullptr); // the library keeps the "C" locale
    if (!std::isfinite(v)) return false;                 // beyond double's range
    out = v;
    return true;
}

} // namespace spatter
