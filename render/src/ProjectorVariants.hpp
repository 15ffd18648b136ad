#pragma once
// The projector's shader variants: one bit per feature a draw's visible decals use and per host
// convention, each becoming a "#define NAME 1" of decal.vert and decal.frag (shaders/decal.frag and
// projector.glsl list what each does).

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace spatter::render_detail {

enum Variant : uint32_t {
    kVariantIds = 1u,
    kVariantWrap = 2u,
    kVariantNormalMap = 4u,
    kVariantFade = 8u,
    kVariantCoverage = 16u,
    kVariantDepthFrame = 32u,
    kVariantNoAngle = 64u,
    kVariantDepthLinear = 128u,
    kVariantClipMinusOne = 256u,
    kVariantStandardZ = 512u,
    kVariantNoNormals = 1024u,
    kVariantNormalWorldSigned = 2048u,
    kVariantNormalWorldUnorm = 4096u,
    kVariantNormalViewUnorm = 8192u,
    kVariantRoughnessAlpha = 16384u,
    kVariantDBuffer = 32768u,
};

// The defines of the set bits, in bit order.
std::vector<std::string> variantDefines(uint32_t bits);

// The bits of the host's conventions in `frame`: depth encoding, clip range, Z direction, normals.
uint32_t conventionBits(const HostFrame& frame);

// The compute program of the projector's shader `file` with `defines`; the error names the projector.
Result<GlProgram> projectorComputeProgram(const std::string& file,
                                          const std::vector<std::string>& defines = {});

} // namespace spatter::render_detail
