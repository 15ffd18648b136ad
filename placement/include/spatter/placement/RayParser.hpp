#pragma once
// RayParser: the text form of a ray used by spatter-place and its ray files. One ray per line,
// "ox oy oz dx dy dz" (world space, any run of blanks between the numbers); '#' starts a comment
// that runs to the end of the line; a line with nothing but blanks and a comment is not a ray.

#include "spatter/placement/Ray.hpp"

#include <cstddef>
#include <string>

namespace spatter {

// One parsed line.
struct RayLine {
    bool isRay = false; // false: blank or comment only (ok is false too)
    bool ok = false;    // the line is a ray and `ray` holds it (tnear 0, tfar infinity)
    Ray ray;
    std::string error; // when isRay and not ok: "line N: ..." saying what was expected
};

// Parses `line` (its number `lineNumber`, used in the error). Each number is read whole as a finite
// decimal number (parseDecimal: no hexadecimal, "nan" or "inf"); anything but exactly six such numbers
// is an error. Never reads outside `line`.
RayLine parseRayLine(const std::string& line, size_t lineNumber);

} // namespace spatter
