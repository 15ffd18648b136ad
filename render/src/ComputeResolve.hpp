#pragma once
// ComputeResolve: the G-buffer blend as one compute pass over the forward path's screen tiles
// (shaders/decal_resolve.comp) instead of a box per decal. Each pixel whose tile holds decals reads the
// host's targets once, applies the tile's decals in drawing order with the boxes' tests and blending,
// and writes the targets once. A GPU may run pixel work on part of its cores only (NVIDIA's H100 and
// H200 run fragment shaders on two of their texture processing clusters) where a compute pass runs on
// all of them; a software rasteriser runs both on the same threads, and there the boxes cost less.

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace spatter::render_detail {

class ComputeResolve {
public:
    // What the pass needs to know of the host's targets: their formats and the shader's defines for them.
    struct Targets {
        std::vector<std::string> defines; // NORMALS_*, ALBEDO_SRGB, ROUGHNESS_* or ROUGHNESS_ALBEDO_ALPHA
        bool srgbAlbedo = false;          // read and written through an RGBA8 view
        GLenum normalFormat = 0;
        GLenum roughnessFormat = 0; // 0: no roughness target of its own
    };
    // The targets of a draw of `o` into `f` when the compute pass can resolve it: the G-buffer blend
    // (not coverage mode, angle rejection on) of a frame in window depth with normals, roughness
    // absent, in R, G or B of its own target or in the albedo's alpha, and targets the pass can load
    // and store: albedo RGBA8 or SRGB8_ALPHA8 (of immutable storage: the pass reads it through an
    // RGBA8 view), normals RG16F, RGBA16F, RGB10_A2 or RGBA8, roughness R8, RG8 or RGBA8. Nothing
    // otherwise.
    static std::optional<Targets> targets(const HostFrame& f, const ProjectorDraw& o);

    // Resolves the decals binned into `f`'s viewport, whose `targets` are those targets() gave, with
    // the variant `defines` (decal.frag's conventions and features). Needs the projector's buffers, the
    // forward bins, the decal textures (units 3 and 4), depth (unit 0) and object IDs (unit 2) bound;
    // changes image units 0 to 2 and the program. Fails when the shader does not build.
    Status run(const HostFrame& f, const Targets& targets, const std::vector<std::string>& defines);

private:
    // The program for `defines`, built on first use.
    Result<GLuint> program(const std::vector<std::string>& defines);

    std::map<std::vector<std::string>, GlProgram> programs_;
};

} // namespace spatter::render_detail
