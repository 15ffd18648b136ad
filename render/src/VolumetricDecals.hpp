#pragma once
// VolumetricDecals: decals whose type is volumetric (DecalType::volumetric) are holes with depth
// (Woodhouse, "3D Decals"), drawn after the geometry pass in two instanced draws per crater variant
// and winding (at most 16 draws whatever the number of decals), from one record per decal
// (shaders/crater.glsl) uploaded every frame:
//   mark    the crater's footprint (its rim, which lies in the z = 0 plane of the decal frame, as a
//           triangle fan) sets the stencil where the surface under it is visible: the G-buffer
//           depth there is within a tolerance of the footprint's, its normal is within the type's
//           largest angle (DecalType::maxAngleDeg) of the decal axis, and (with IDs) the pixel's
//           object decal ID is the decal's. The angle keeps a crater near a concave corner off the
//           adjacent surface, whose depth near the corner line is close to the footprint's.
//           Overlapping footprints set the same bit: a union, one hole.
//   crater  the crater mesh (CraterMesh.hpp), oriented by the decal frame and scaled by the decal
//           size, is drawn where the stencil is set, back faces culled, with the depth test
//           "farther wins" (GL_LESS under reversed-Z) against the surface's depth: every crater
//           point lies behind the rim plane, so the hole replaces the surface, and where craters
//           overlap the deeper cavity shows instead of one cup's wall standing inside another's
//           hole. Pixels of a footprint that no crater covers keep the surface, so nothing behind
//           the surface can show through. Albedo, roughness and metallic are the surface's,
//           fetched from a copy of the G-buffer taken before the pass at the point of the surface
//           above the crater point (its projection along the decal axis), darkened with depth;
//           the normal is the crater's, so the lighting pass shades the hole. In the coverage view
//           the crater marks its pixels covered.
// Both draws are cut by the decal's two clip planes (CraterClips, gl_ClipDistance): near an edge of
// a crate or a pillar, or behind a thin wall, the cup and its footprint stop where the solid ends.

#include "GBuffer.hpp"
#include "GlObjects.hpp"

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace spatter::render_detail {

class VolumetricDecals {
public:
    static constexpr int kVariants = 4; // crater variants; a decal uses variant id % kVariants

    // Builds the crater variants and the programs.
    Status create();

    // The volumetric decals to draw (`types` indexed by Decal::type) and their clip planes (parallel to
    // `decals`; none past its end); those naming a missing object or type, with a non-finite or
    // degenerate frame or size are skipped and counted.
    void setDecals(const std::vector<Decal>& decals, const std::vector<CraterClips>& clips,
                   const std::vector<DecalType>& types, size_t objectCount);
    size_t size() const { return decals_.size(); }
    size_t invalidCount() const { return invalid_; }

    // Draws every decal into `gbuffer` (attachments 0..2, the coverage attachment when `coverage`,
    // depth and stencil). `transforms` are the objects' world transforms, `eye` the camera position;
    // the pixels' object decal IDs (`idTexture`) are compared with the decals' when `compareIds`. The
    // frame block must be bound. Returns the draws.
    size_t draw(const GBuffer& gbuffer, GLuint idTexture, bool compareIds, bool coverage,
                const std::vector<glm::dmat4>& transforms, const glm::dvec3& eye);

private:
    struct Variant {
        uint32_t firstIndex = 0, indexCount = 0;         // the crater
        uint32_t footprintFirst = 0, footprintCount = 0; // the flattened rim, a fan
        float depth = 0.0f;                              // deepest point, in units of the radius
    };
    std::vector<Decal> decals_;
    std::vector<CraterClips> clips_; // per decal
    std::vector<float> cosMaxAngle_; // per decal, from its type
    size_t invalid_ = 0;
    Variant variants_[kVariants];
    GlBuffer vertices_, indices_, records_;
    size_t recordCapacity_ = 0; // bytes
    GlVertexArray vao_;
    GlProgram markProgram_, markIdsProgram_, craterProgram_;
    GlTexture albedoCopy_, materialCopy_;
    int copyWidth_ = 0, copyHeight_ = 0;
};

} // namespace spatter::render_detail
