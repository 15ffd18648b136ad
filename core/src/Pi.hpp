#pragma once
// Pi in the two precisions the core's sources compute in.

namespace spatter {

constexpr double kPi = 3.14159265358979323846;
constexpr float kPiF = 3.14159265358979323846f;

} // namespace spatter
