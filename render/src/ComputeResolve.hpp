#pragma once
// ComputeResolve: the G-buffer blend, or the DBuffer path's decal buffers, as one compute pass over
// the forward path's screen tiles (shaders/decal_resolve.comp) instead of a box per decal. Each pixel
// whose tile holds decals reads the host's targets once, applies the tile's decals in drawing order
// with the boxes' tests and blending, and writes its targets once. A GPU may run pixel work on part of
// its cores only (NVIDIA's H100 and H200 run fragment shaders on two of their texture processing
// clusters) where a compute pass runs on all of them; a software rasteriser runs both on the same
// threads, and there the boxes cost less.

#include "DecalBuffers.hpp"
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
    // The textures the pass writes, their formats and the shader's defines for them.
    struct Targets {
        std::vector<std::string> defines; // NORMALS_*, ALBEDO_SRGB, ROUGHNESS_* or ROUGHNESS_ALBEDO_ALPHA
        GLuint albedo = 0, normals = 0, roughness = 0; // roughness 0: no target of its own
        bool srgbAlbedo = false;                       // read and written through an RGBA8 view
        GLenum normalFormat = 0;
        GLenum roughnessFormat = 0;
        int roughnessChannel = -1; // 0..2 in `roughness`; -1: none, or in the albedo's alpha
    };
    // The targets of a draw of `o` into `f` when the compute pass can resolve it, a frame in window
    // depth with normals and angle rejection on (not coverage mode):
    // - the G-buffer blend into targets the pass can load and store: albedo RGBA8 or SRGB8_ALPHA8 (of
    //   immutable storage: the pass reads it through an RGBA8 view), normals RG16F, RGBA16F, RGB10_A2
    //   or RGBA8, roughness absent, in R, G or B of R8, RG8 or RGBA8 of its own, or in the albedo's
    //   alpha;
    // - the DBuffer path into `dbuffer`, prepared for the frame (the host's normals are only read).
    // Nothing otherwise.
    static std::optional<Targets> targets(const HostFrame& f, const ProjectorDraw& o,
                                          const DecalBuffers& dbuffer);

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
