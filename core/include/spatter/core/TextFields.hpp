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

// What parseNumber does with a value strtod reports out of double's range (ERANGE): one that
// overflows (read as +-HUGE_VAL) or underflows (read as zero or a subnormal).
enum class OutOfRange { Reject, Accept };

// Reads all of `text` as one number the way strtod reads it: decimal or hexadecimal, "inf" and
// "nan" included, blanks before it skipped; nothing may follow it (trim the text first to allow
// blanks there). Returns false, with `out` unspecified, for text that holds no number, anything
// after the number, and (unless `outOfRange` says Accept) a value out of double's range.
bool parseNumber(const std::string& text, double& out, OutOfRange outOfRange = OutOfRange::Reject);

} // namespace spatter
