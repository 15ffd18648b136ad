#pragma once
// DecalRefit: a decal laid again on the surface that is drawn. Placement lays a decal on the surface
// its shot hits; where that is a collision proxy, the drawn surface lies within the proxy's bound but
// its facets are tilted against the proxy's, and a decal laid in the proxy facet's plane covers a
// footprint the drawn surface's own decal would not. Given where the line along the decal's
// projection axis meets the drawn surface, and that surface's normal there, relaidDecal gives the
// decal placement would have laid there: its centre on that point and its frame built on that normal
// as placement builds a frame (the shot as hint, then turned about the normal by the decal's own
// rotation, read back from its frame), with its projection axis, size and look kept. It is the
// reference for a decal pass that reads the drawn surface, and what `spatter-bench tradeoff
// --iou-breakdown` measures as its drawn probe (ACCURACY.md, "What the drawn surface could
// correct").

#include "spatter/core/Decal.hpp"

#include <glm/glm.hpp>
#include <optional>

namespace spatter {

// `d` (object space, its object's linear part to world `toWorld`) laid again at `point` on a surface
// of normal `normal` (both object space; the normal need not be unit and is turned to face the decal's
// normal), its box `halfDepth` deep. The hint is the shot, the decal's projection axis reversed; a
// decal along its normal, whose shot the record does not keep, is turned instead by the least rotation
// that takes its normal to the drawn one, and stays along its (new) normal. Empty for a decal without
// an orientation, a value that is not finite, a zero normal, a normal 89 degrees or more from the
// decal's (in world space), a negative half-depth or a `toWorld` that cannot be inverted.
std::optional<Decal> relaidDecal(const Decal& d, const glm::dmat3& toWorld, const glm::vec3& point,
                                 const glm::vec3& normal, float halfDepth);

// The angle in degrees, world space, between the shot of `d` (its projection axis) and the normal of
// `laid`, d laid again (relaidDecal): what placement tests against DecalType::maxAngleDeg on the surface
// a shot hits. Empty for a decal along its normal (slant 0), whose shot the record does not keep.
std::optional<double> laidShotAngleDeg(const Decal& d, const Decal& laid, const glm::dmat3& toWorld);

} // namespace spatter
