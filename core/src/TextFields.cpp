#include "spatter/core/TextFields.hpp"

#include <cerrno>
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

bool parseNumber(const std::string& text, double& out, OutOfRange outOfRange) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && (outOfRange == OutOfRange::Accept || errno != ERANGE);
}

} // namespace spatter
