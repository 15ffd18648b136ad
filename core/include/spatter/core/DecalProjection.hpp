#pragma once
// DecalProjection: the axis along which a decal's texture is projected onto the drawn surface.
//
// Along the normal, the box is a right prism over the decal's rectangle. Along the shot, its depth
// lines run along the ray that placed it: the box is a parallelepiped whose cross-section parallel to
// the decal plane is the same rectangle, shifted along the ray with the distance from the plane. A
// drawn surface that lies off the collision surface then receives the footprint centred where the
// same shot meets it, not where the normal through the collision hit does.
//
// A Decal keeps its axis as its slant: the slopes (axis . tangent, axis . bitangent) / (axis . normal)
// of its frame (Decal::frame()'s tangent and bitangent, mirrored or not), two half floats in 32 bits,
// 0 along the normal. The box maps the unit cube's point (u, v, w) to
//   centre + u * w/2 * tangent + v * h/2 * bitangent + w * halfDepth * (normal + sx * tangent + sy *
//   bitangent)
// so it spans the same distance, halfDepth, on either side of the decal plane whatever the slant.
// shaders/decal_data.glsl unpacks the same bits.

#include <cstdint>
#include <glm/glm.hpp>

namespace spatter {

// How the decals of a type are projected (DecalType::projection).
enum class Projection : uint8_t {
    Normal = 0, // along the surface normal at the hit
    Shot = 1,   // along the reversed ray of the shot that placed it (spawn, spawnBatch)
};

// The largest angle between the projection axis and the decal normal: an axis farther from the
// normal is turned towards it in their common plane, to this angle. Its slope, tan 85 degrees, keeps
// the box within 11.5 half-depths of its centre along the plane.
constexpr double kMaxSlantDeg = 85.0;

// The slopes packed as two half floats (x in bits 0-15), the pair scaled down to a length of at most
// tan kMaxSlantDeg, and a pair with a value that is not finite taken as (0, 0).
uint32_t packSlant(const glm::vec2& slopes);

// The slopes of packed bits: (0, 0) for 0.
glm::vec2 unpackSlant(uint32_t bits);

// Whether `bits` are a slant packSlant makes: both halves finite, within kMaxSlantDeg of the normal.
bool validSlant(uint32_t bits);

// The slant of `axis` in the orthonormal frame (t, b, n), turned to kMaxSlantDeg when farther from
// n; 0 (along the normal) when `axis` is zero, not finite or does not point to n's side.
uint32_t slantOf(const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n, const glm::dvec3& axis);

} // namespace spatter
