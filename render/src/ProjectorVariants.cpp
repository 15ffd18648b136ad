#include "ProjectorVariants.hpp"

#include "ProjectorShaders.hpp"
#include "ShaderProgram.hpp"

namespace spatter::render_detail {

namespace {

constexpr const char* kVariantNames[] = {"IDS",
                                         "WRAP",
                                         "NORMAL_MAP",
                                         "FADE",
                                         "COVERAGE",
                                         "DEPTH_FRAME",
                                         "NO_ANGLE",
                                         "DEPTH_LINEAR",
                                         "CLIP_MINUS_ONE",
                                         "STANDARD_Z",
                                         "NO_NORMALS",
                                         "NORMAL_WORLD_SIGNED",
                                         "NORMAL_WORLD_UNORM",
                                         "NORMAL_VIEW_UNORM",
                                         "ROUGHNESS_ALPHA",
                                         "DBUFFER"};

} // namespace

std::vector<std::string> variantDefines(uint32_t bits) {
    std::vector<std::string> d;
    for (size_t i = 0; i < sizeof(kVariantNames) / sizeof(kVariantNames[0]); ++i)
        if (bits & (1u << i)) d.push_back(kVariantNames[i]);
    return d;
}

uint32_t conventionBits(const HostFrame& f) {
    uint32_t bits = 0;
    if (f.depth.encoding == DepthEncoding::LinearView) bits |= kVariantDepthLinear;
    if (f.depth.clip == ClipDepth::MinusOneToOne) bits |= kVariantClipMinusOne;
    if (!f.depth.reversedZ && f.depth.encoding == DepthEncoding::Window) bits |= kVariantStandardZ;
    if (f.normals.texture == 0) return bits | kVariantNoNormals;
    switch (f.normals.encoding) {
    case NormalEncoding::WorldSigned:
        return bits | kVariantNormalWorldSigned;
    case NormalEncoding::WorldUnorm:
        return bits | kVariantNormalWorldUnorm;
    case NormalEncoding::ViewUnorm:
        return bits | kVariantNormalViewUnorm;
    case NormalEncoding::OctahedralWorld:
        break;
    }
    return bits;
}

Result<GlProgram> projectorComputeProgram(const std::string& file, const std::vector<std::string>& defines) {
    Result<GlProgram> p =
        buildProgram(shaderLibrary(kProjectorShaders), {{GL_COMPUTE_SHADER, file.c_str()}}, defines);
    if (!p) return fail("projector: " + p.error());
    return p;
}

} // namespace spatter::render_detail
