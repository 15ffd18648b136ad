#pragma once
// Whole numbers on the tools' command lines, as bare digits; decimal numbers go through core's
// parseDecimal (TextFields.hpp). Every tool reads numbers through these, so that a number means the
// same in each.

#include <cstdint>
#include <string>

namespace spatter::cli {

// Reads all of `text` as a whole number in 0..max: digits only (no sign, blank, point or exponent).
// False for anything else and for a larger value.
bool parseWhole(const std::string& text, uint64_t max, uint64_t& out);

} // namespace spatter::cli
