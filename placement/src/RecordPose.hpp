#pragma once
// RecordPose: moves a placed record's decal box, placed on a skinned or morphed object at one time of
// the scene's first animation, to the pose of another, riding the render triangle it was placed on
// (the record's "anchor"). What lets spatter-render draw decals that spatter-place placed at another
// time on the surface they were placed on.

#include "spatter/core/Scene.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalRecords.hpp"

#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace spatter {

class RecordPoses {
public:
    // Keeps a reference to `scene` (validated), whose world is moved by `offset` from the one its
    // animation describes.
    RecordPoses(const Scene& scene, const glm::dvec3& offset)
        : scene_(scene), offset_(offset), evaluator_(scene) {}

    // The world frame of `anchor` on `object`'s render mesh at time t (triangleFrame); empty for a
    // triangle out of range or collapsed at that pose.
    std::optional<glm::dmat4> frameAt(uint32_t object, const SurfaceAnchor& anchor, double t);

private:
    const Scene& scene_;
    glm::dvec3 offset_;
    SceneEvaluator evaluator_;
    std::map<std::pair<uint32_t, double>, std::vector<glm::dvec3>> posed_; // world positions by (object, t)
};

// `box` carried from the frame `from` to the frame `to`: its centre, axes and projection axis keep
// their place relative to the frame.
WorldDecalBox moveBox(const WorldDecalBox& box, const glm::dmat4& from, const glm::dmat4& to);

} // namespace spatter
