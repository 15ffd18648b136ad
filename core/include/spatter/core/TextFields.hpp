#pragma once
// TextFields: the fields of a line of option or setting text ("1,2,3", "eye=0,1,2;fov=45", "3x4"),
// cut at a separator, stripped of blanks and read as numbers. Used by the camera string and the
// command-line tools, so that they read the same text the same way.

#include <string>
#include <vector>

namespace spatter {

// `text` without the blanks (space, tab, CR, LF) at either end; "" when it is all blanks.
std::string trimBlanks(const std::string& text);

// The parts of `text` between the separators `sep`, in order and untrimmed, empty ones kept:
// "a,,b" gives {"a", "", "b"}, "a," gives {"a", ""} and "" gives {""}. Never empty.
std::vector<std::string> splitFields(const std::string& text, char sep);

// Reads all of `text` as a decimal number: an optional sign, digits with an optional point, an
// optional exponent ("e-3"). False, with `out` unchanged, for anything else (blanks, hexadecimal,
// "inf", "nan") and for a value beyond double's range; one that underflows reads as zero or a
// subnormal. The tools, the camera string and the ray files read numbers through it, so that a number
// means the same everywhere.
bool parseDecimal(const std::string& text, double& out);

} // namespace spatter
