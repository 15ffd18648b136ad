#pragma once
// DeformingProxy: a collision proxy for a skinned or morphed object that holds its bound over the
// object's animations, not only at rest.
//
// A proxy simplified at the rest pose keeps no vertices where nothing curves at rest: an arm that
// stands straight at rest loses every ring between shoulder and hand, and once the elbow bends the
// proxy cuts across the bend (on builtin:skinned-arm, 0.35 m at a 0.5 cm rest bound). So the proxy is
// also simplified in the pose where the rest proxy strays most: every vertex a simplifier keeps there
// is a vertex of the posed render mesh, which the proxy then maps back to the rest pose (through the
// nearest point of the posed render surface and its barycentric coordinates), where it takes the
// render vertex's own joint weights and morph deltas (transferDeformation finds them again). Of the
// two proxies the one with the smaller bound over the poses (boundOverPoses) is kept, and its
// errorBound is that bound, so that decal boxes sized by it hold the drawn surface at every sampled
// pose. When the proxy builder keeps the render mesh itself (ProxySource::OwnMesh), it moves exactly
// as it is drawn: its bound stays 0 and no pose is sampled.

#include "spatter/core/PoseBound.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/VertexDeformation.hpp"

namespace spatter {

struct DeformingProxy {
    Proxy proxy;                   // rest pose; errorBound = poses.bound; no drawnNormals
    VertexDeformation deformation; // of proxy.mesh, transferred from the render mesh
    PoseBound poses;               // its bound over the poses
    // The proxy simplified at rest over the poses: its bound (boundOverPoses, restCertified), or only
    // its sampled distances (sampledOverPoses, a lower bound) where the proxy simplified in a pose
    // certifies below them, so that the rest proxy loses without being certified.
    PoseBound restPoses;
    bool restCertified = false;
    bool simplifiedPosed = false; // true: simplified in the pose poses.worstTime of restPoses
};

// Builds the proxy of `scene.objects[object]` (skinned or morphed) with `settings`, sampling each
// animation `samples` times (see PoseBound.hpp). Fails like buildProxy and boundOverPoses, and for an
// object that neither is skinned nor has morph targets.
Result<DeformingProxy> buildDeformingProxy(const Scene& scene, size_t object, const ProxySettings& settings,
                                           int samples = 128);

// Whether buildObjectProxy gives `o` a deforming proxy: a dynamic object that is skinned or morphed.
bool takesDeformingProxy(const SceneObject& o);

// The proxy of `scene.objects[object]`: buildDeformingProxy for a dynamic object that is skinned or
// morphed (its bound holds over the animation; `progress` is not called), otherwise buildProxy of its
// render mesh against its authored collider, if it has one. With settings.cacheDirectory a deforming
// object's proxy is cached too (ProxyCache.hpp), keyed by its rest proxy's key, its joint influences
// and morph targets, and its transform, joint matrices and morph weights at every sampled pose, so a
// start from the cache measures no pose; cached is true then, and false after poses were measured.
// Fails for an object out of range.
Result<Proxy> buildObjectProxy(const Scene& scene, size_t object, const ProxySettings& settings,
                               const ProgressCallback& progress = {});

} // namespace spatter
