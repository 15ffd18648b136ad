#include "cli/Numbers.hpp"

#include <charconv>
#include <cstdlib>

namespace spatter::cli {

bool parseWhole(const std::string& text, uint64_t max, uint64_t& out) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
    uint64_t v = 0;
    const std::from_chars_result r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || v > max) return false;
    out = v;
    return true;
}

} // namespace spatter::cli
