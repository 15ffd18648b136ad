#include "ComputeResolve.hpp"

#include "ProjectorVariants.hpp"

namespace spatter::render_detail {

namespace {

constexpr GLuint kGroupSize = 8; // decal_resolve.comp's local size, each way

GLint internalFormat(GLuint texture) {
    GLint format = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    return format;
}

bool immutable(GLuint texture) {
    GLint value = GL_FALSE;
    glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_FORMAT, &value);
    return value == GL_TRUE;
}

// The shader's name for the format of a normal or roughness target; empty for one it does not take.
std::string normalFormat(GLint format) {
    switch (format) {
    case GL_RG16F:
        return "NORMALS_RG16F";
    case GL_RGBA16F:
        return "NORMALS_RGBA16F";
    case GL_RGB10_A2:
        return "NORMALS_RGB10A2";
    case GL_RGBA8:
        return "NORMALS_RGBA8";
    default:
        return "";
    }
}

std::string roughnessFormat(GLint format) {
    switch (format) {
    case GL_R8:
        return "ROUGHNESS_R8";
    case GL_RG8:
        return "ROUGHNESS_RG8";
    case GL_RGBA8:
        return "ROUGHNESS_RGBA8";
    default:
        return "";
    }
}

// The G-buffer blend's targets: the host's.
std::optional<ComputeResolve::Targets> gbufferTargets(const HostFrame& f) {
    ComputeResolve::Targets t;
    t.normals = f.normals.texture;
    t.normalFormat = GLenum(internalFormat(f.normals.texture));
    const std::string normals = normalFormat(GLint(t.normalFormat));
    if (normals.empty()) return std::nullopt;
    t.defines.push_back(normals);
    t.albedo = f.albedoTexture;
    const GLint albedo = internalFormat(f.albedoTexture);
    t.srgbAlbedo = albedo == GL_SRGB8_ALPHA8 && immutable(f.albedoTexture);
    if (t.srgbAlbedo)
        t.defines.push_back("ALBEDO_SRGB");
    else if (albedo != GL_RGBA8)
        return std::nullopt;
    if (f.roughness.texture == 0) return t;
    if (f.roughness.texture == f.albedoTexture) { // in the albedo's alpha
        if (f.roughness.channel != 3) return std::nullopt;
        t.defines.push_back("ROUGHNESS_ALBEDO_ALPHA");
        return t;
    }
    t.roughness = f.roughness.texture;
    t.roughnessChannel = f.roughness.channel;
    t.roughnessFormat = GLenum(internalFormat(f.roughness.texture));
    const std::string roughness = roughnessFormat(GLint(t.roughnessFormat));
    if (f.roughness.channel >= 3 || roughness.empty()) return std::nullopt;
    t.defines.push_back(roughness);
    return t;
}

// The DBuffer path's targets: the projector's decal buffers (DecalBuffers' formats).
ComputeResolve::Targets dbufferTargets(const DecalBuffers& dbuffer) {
    ComputeResolve::Targets t;
    t.defines = {"NORMALS_RGBA16F", "ALBEDO_SRGB", "ROUGHNESS_RGBA8"};
    t.albedo = dbuffer.albedo();
    t.srgbAlbedo = true;
    t.normals = dbuffer.normal();
    t.normalFormat = GL_RGBA16F;
    t.roughness = dbuffer.material();
    t.roughnessFormat = GL_RGBA8;
    t.roughnessChannel = 0;
    return t;
}

} // namespace

std::optional<ComputeResolve::Targets> ComputeResolve::targets(const HostFrame& f, const ProjectorDraw& o,
                                                               const DecalBuffers& dbuffer) {
    if (o.coverageTexture != 0 || !o.angleReject) return std::nullopt;
    if (f.depth.encoding != DepthEncoding::Window || f.normals.texture == 0) return std::nullopt;
    if (o.path == ProjectorPath::DBuffer) return dbufferTargets(dbuffer);
    if (o.path != ProjectorPath::GBufferBlend) return std::nullopt;
    return gbufferTargets(f);
}

Result<GLuint> ComputeResolve::program(const std::vector<std::string>& defines) {
    const auto found = programs_.find(defines);
    if (found != programs_.end()) return found->second.get();
    Result<GlProgram> p = projectorComputeProgram("decal_resolve.comp", defines);
    if (!p) return fail(p.error());
    return programs_.emplace(defines, std::move(p.value())).first->second.get();
}

Status ComputeResolve::run(const HostFrame& f, const Targets& t, const std::vector<std::string>& variant) {
    std::vector<std::string> defines = variant;
    defines.insert(defines.end(), t.defines.begin(), t.defines.end());
    Result<GLuint> p = program(defines);
    if (!p) return fail(p.error());

    // An sRGB target is loaded and stored through an RGBA8 view of it (sRGB formats are no image formats).
    GlTexture view;
    GLuint albedo = t.albedo;
    if (t.srgbAlbedo) {
        GLuint name = 0;
        glGenTextures(1, &name);
        glTextureView(name, GL_TEXTURE_2D, t.albedo, GL_RGBA8, 0, 1, 0, 1);
        view = GlTexture(name);
        albedo = name;
    }
    glBindImageTexture(0, albedo, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glBindImageTexture(1, t.normals, 0, GL_FALSE, 0, GL_READ_WRITE, t.normalFormat);
    if (t.roughness != 0)
        glBindImageTexture(2, t.roughness, 0, GL_FALSE, 0, GL_READ_WRITE, t.roughnessFormat);
    glUseProgram(p.value());
    glUniform4i(0, f.x, f.y, f.width, f.height);
    glUniform1i(1, t.roughness != 0 ? t.roughnessChannel : -1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glDispatchCompute((GLuint(f.width) + kGroupSize - 1) / kGroupSize,
                      (GLuint(f.height) + kGroupSize - 1) / kGroupSize, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
    return {};
}

} // namespace spatter::render_detail
