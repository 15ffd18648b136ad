#pragma once
// Numbers on the tools' command lines: decimal text only ("12", "-0.5", "1e-3"), with no blanks,
// hexadecimal, "inf" or "nan"; whole numbers as bare digits. Every tool reads numbers through these,
// so that a number means the same in each.

#include <cstdint>
#include <string>

namespace spatter::cli {

// Reads all of `text` as a decimal number: an optional sign, digits with an optional point, an
// optional exponent ("e-3"). False for anything else, and for a value beyond double's range; one that
// underflows reads as zero or a subnormal.
bool parseDecimal(const std::string& text, double& out);

// Reads all of `text` as a whole number in 0..max: digits only (no sign, blank, point or exponent).
// False for anything else and for a larger value.
bool parseWhole(const std::string& text, uint64_t max, uint64_t& out);

} // namespace spatter::cli
