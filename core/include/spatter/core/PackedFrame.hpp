#pragma once
// PackedFrame: an orthonormal frame in 64 bits, as a Decal and the GPU's decal record keep it. A
// unit quaternion by its three smallest components (the largest is implied: positive, and the unit
// length gives its size), each in 20 bits over [-1/sqrt(2), 1/sqrt(2)] with 0 exact, and a mirrored
// flag for a left-handed frame. Unpacked, a frame is orthonormal to float precision and each axis
// lies within kPackedFrameError of the one packed (each component is rounded to within 6.7e-7; 3.8e-6
// is the largest axis error measured over 20 million rotations, those nearest the worst case included).
//
// Bits: 0-59 the three components (20 each, offset by 2^19, in the order w, x, y, z with the
// largest left out); 60-61 which component is the largest (0 w, 1 x, 2 y, 3 z); 62 mirrored; 63 set
// for every frame. 0 is no orientation: what a degenerate frame packs to, which unpacks to zero.
// shaders/decal_data.glsl unpacks the same bits.

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace spatter {

constexpr uint64_t kNoOrientation = 0;
// The largest distance between an axis packed and the axis unpacked.
constexpr double kPackedFrameError = 4e-6;
// The identity rotation, not mirrored.
constexpr uint64_t kIdentityOrientation =
    (uint64_t(1) << 63) | (uint64_t(1) << 59) | (uint64_t(1) << 39) | (uint64_t(1) << 19);

// Packs the rotation whose columns are t, b and n, an orthonormal right-handed frame (not checked;
// Decal::setFrame makes any frame one first), and the mirrored flag: Shepperd's method without a
// branch, whose choice of the largest component is the one packing needs. kNoOrientation where a
// component is not finite.
uint64_t packFrame(const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n, bool mirrored);

// Packs a unit quaternion (its length is not checked: it is taken as unit) and the mirrored flag.
// A quaternion that is not finite or too short to be a direction packs to kNoOrientation.
uint64_t packOrientation(const glm::dquat& unit, bool mirrored);

// The unit quaternion of `bits`, largest component positive; the zero quaternion for kNoOrientation
// or any value without bit 63.
glm::dquat unpackOrientation(uint64_t bits);

inline bool hasOrientation(uint64_t bits) {
    return (bits >> 63) != 0;
}

inline bool packedMirrored(uint64_t bits) {
    return (bits >> 62 & 1u) != 0;
}

} // namespace spatter
