#include "HostFrameCheck.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <utility>

namespace spatter::render_detail {

namespace {

struct KnownFormat {
    GLenum format;
    FormatFacts facts;
};

// channels, depth, integer, signed, renderable
constexpr KnownFormat kFormats[] = {
    {GL_DEPTH_COMPONENT16, {1, true, false, false, false}},
    {GL_DEPTH_COMPONENT24, {1, true, false, false, false}},
    {GL_DEPTH_COMPONENT32, {1, true, false, false, false}},
    {GL_DEPTH_COMPONENT32F, {1, true, false, false, false}},
    {GL_DEPTH24_STENCIL8, {1, true, false, false, false}},
    {GL_DEPTH32F_STENCIL8, {1, true, false, false, false}},
    {GL_R8, {1, false, false, false, true}},
    {GL_R16, {1, false, false, false, true}},
    {GL_R16F, {1, false, false, true, true}},
    {GL_R32F, {1, false, false, true, true}},
    {GL_R8UI, {1, false, true, false, true}},
    {GL_R16UI, {1, false, true, false, true}},
    {GL_R32UI, {1, false, true, false, true}},
    {GL_RG8, {2, false, false, false, true}},
    {GL_RG8_SNORM, {2, false, false, true, true}},
    {GL_RG16, {2, false, false, false, true}},
    {GL_RG16_SNORM, {2, false, false, true, true}},
    {GL_RG16F, {2, false, false, true, true}},
    {GL_RG32F, {2, false, false, true, true}},
    {GL_RGB10_A2, {4, false, false, false, true}},
    {GL_RGBA8, {4, false, false, false, true}},
    {GL_SRGB8_ALPHA8, {4, false, false, false, true}},
    {GL_RGBA8_SNORM, {4, false, false, true, true}},
    {GL_RGBA16, {4, false, false, false, true}},
    {GL_RGBA16_SNORM, {4, false, false, true, true}},
    {GL_RGBA16F, {4, false, false, true, true}},
    {GL_RGBA32F, {4, false, false, true, true}},
    {GL_R11F_G11F_B10F, {3, false, false, false, true}},
};

struct Level {
    GLenum format = 0;
    int width = 0, height = 0;
};

// Level 0 of a GL_TEXTURE_2D, or an error naming `field`.
std::string level(GLuint texture, const char* field, Level& out) {
    if (texture == 0 || !glIsTexture(texture))
        return std::string(field) + ": " + std::to_string(texture) + " is not a texture";
    GLint target = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        return std::string(field) + ": texture " + std::to_string(texture) + " is not a GL_TEXTURE_2D";
    GLint w = 0, h = 0, f = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &f);
    out = {GLenum(f), w, h};
    return {};
}

std::string formatName(GLenum f) {
    char text[32];
    std::snprintf(text, sizeof text, "0x%04X", unsigned(f));
    return text;
}

// A texture of the frame: it exists, holds the viewport, and `accept` takes its format (else `need`).
template <class Accept>
std::string checkTexture(GLuint texture, const char* field, const HostFrame& frame, Accept accept,
                         const char* need) {
    Level l;
    if (std::string p = level(texture, field, l); !p.empty()) return p;
    if (int64_t(frame.x) + frame.width > l.width || int64_t(frame.y) + frame.height > l.height)
        return std::string(field) + ": texture of " + std::to_string(l.width) + "x" +
               std::to_string(l.height) + " does not hold the viewport " + std::to_string(frame.x) + "," +
               std::to_string(frame.y) + " " + std::to_string(frame.width) + "x" +
               std::to_string(frame.height);
    if (!accept(formatFacts(l.format)))
        return std::string(field) + ": format " + formatName(l.format) + " is not supported (" + need + ")";
    return {};
}

bool finiteMatrix(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool invertible(const glm::dmat4& m) {
    const double det = glm::determinant(m);
    return finiteMatrix(m) && std::isfinite(det) && det != 0.0 && finiteMatrix(glm::inverse(m));
}

// The camera of `f`, whose fields the error names as `frame`'s ("HostFrame", "ForwardFrame").
std::string cameraProblem(const HostFrame& f, const std::string& frame) {
    if (!invertible(f.view)) return frame + ".view: not a finite invertible matrix";
    if (!invertible(f.projection)) return frame + ".projection: not a finite invertible matrix";
    if (!std::isfinite(f.eye.x) || !std::isfinite(f.eye.y) || !std::isfinite(f.eye.z))
        return frame + ".eye: not finite";
    if (f.depth.encoding != DepthEncoding::Window) return {};
    // Two points on the view axis in front of the camera: which one gets the larger depth?
    const glm::dmat4 inv = glm::inverse(f.projection);
    const double a = f.depth.clip == ClipDepth::ZeroToOne ? 0.25 : -0.5, b = 0.5;
    const glm::dvec4 pa = inv * glm::dvec4(0.0, 0.0, a, 1.0), pb = inv * glm::dvec4(0.0, 0.0, b, 1.0);
    const double za = pa.z / pa.w, zb = pb.z / pb.w;
    if (!std::isfinite(za) || !std::isfinite(zb) || za == zb)
        return frame + ".projection: maps no depth range";
    const bool reversed = zb > za; // a larger depth is nearer
    if (reversed != f.depth.reversedZ)
        return frame + (frame == "HostFrame" ? ".depth" : "") +
               ".reversedZ: " + (f.depth.reversedZ ? "true" : "false") + ", but the projection gives " +
               (reversed ? "nearer" : "farther") + " points larger depths";
    return {};
}

// Why `texture`, named `name`, cannot hold normals in the encoding of `f.normals`, or empty.
std::string normalTextureProblem(GLuint texture, const char* name, const HostFrame& f) {
    const bool oct = f.normals.encoding == NormalEncoding::OctahedralWorld;
    const bool isSigned = oct || f.normals.encoding == NormalEncoding::WorldSigned;
    return checkTexture(
        texture, name, f,
        [oct, isSigned](const FormatFacts& k) {
            return k.renderable && !k.integer && k.channels >= (oct ? 2 : 3) && (!isSigned || k.isSigned);
        },
        oct        ? "a signed two-channel format (RG16F, RG16_SNORM)"
        : isSigned ? "a signed format of three or more channels (RGBA16F)"
                   : "a colour format of three or more channels (RGBA8, RGB10_A2)");
}

// Two fields of the frame that the pass uses naming one texture: it would read a texture it writes,
// or write one twice. Roughness in the albedo target's alpha is the one sharing allowed.
std::string sharedTextureProblem(const HostFrame& f, const ProjectorDraw& options) {
    const bool coverage = options.coverageTexture != 0;
    const bool blend = !coverage && options.path == ProjectorPath::GBufferBlend;
    const std::pair<GLuint, const char*> used[] = {
        {f.depth.texture, "HostFrame.depth.texture"},
        {f.normals.texture, "HostFrame.normals.texture"},
        {f.faceNormalTexture, "HostFrame.faceNormalTexture"},
        {f.objectIdTexture, "HostFrame.objectIdTexture"},
        {blend ? f.albedoTexture : 0u, "HostFrame.albedoTexture"},
        {blend ? f.roughness.texture : 0u, "HostFrame.roughness.texture"},
        {options.coverageTexture, "ProjectorDraw.coverageTexture"}};
    const size_t albedo = 4, roughness = 5;
    for (size_t j = 1; j < std::size(used); ++j)
        for (size_t i = 0; i < j; ++i)
            if (used[j].first != 0 && used[j].first == used[i].first &&
                !(i == albedo && j == roughness && f.roughness.channel == 3))
                return std::string(used[j].second) + ": the same texture as " + used[i].second +
                       (j == roughness ? " (roughness may share the albedo target only in its alpha)" : "");
    return {};
}

} // namespace

FormatFacts formatFacts(GLenum internalFormat) {
    for (const KnownFormat& k : kFormats)
        if (k.format == internalFormat) return k.facts;
    return {};
}

GLenum textureFormat(GLuint texture) {
    Level l;
    return level(texture, "", l).empty() ? l.format : 0;
}

std::string hostFrameProblem(const HostFrame& f, const ProjectorDraw& options) {
    if (options.path != ProjectorPath::GBufferBlend && options.path != ProjectorPath::DBuffer)
        return "ProjectorDraw.path " + std::to_string(int(options.path)) + " names no ProjectorPath";
    if (f.width <= 0 || f.height <= 0 || f.x < 0 || f.y < 0)
        return "HostFrame viewport " + std::to_string(f.x) + "," + std::to_string(f.y) + " " +
               std::to_string(f.width) + "x" + std::to_string(f.height) +
               ": the size must be positive and the corner not negative";
    if (std::string p = cameraProblem(f, "HostFrame"); !p.empty()) return p;
    const bool window = f.depth.encoding == DepthEncoding::Window;
    std::string p = checkTexture(
        f.depth.texture, "HostFrame.depth.texture", f,
        [window](const FormatFacts& k) {
            return window ? (k.depth || (k.channels >= 1 && !k.integer)) : (k.isSigned && !k.integer);
        },
        window ? "a depth format, or a float or normalised colour format" : "a float format (R32F, R16F)");
    if (!p.empty()) return p;
    for (const auto& [texture, name] : {std::pair{f.normals.texture, "HostFrame.normals.texture"},
                                        std::pair{f.faceNormalTexture, "HostFrame.faceNormalTexture"}})
        if (texture != 0)
            if (p = normalTextureProblem(texture, name, f); !p.empty()) return p;
    const bool coverage = options.coverageTexture != 0;
    if (coverage) {
        p = checkTexture(
            options.coverageTexture, "ProjectorDraw.coverageTexture", f,
            [](const FormatFacts& k) { return k.renderable && !k.integer; }, "a colour format (R8)");
        if (!p.empty()) return p;
    } else if (options.path == ProjectorPath::GBufferBlend) {
        p = checkTexture(
            f.albedoTexture, "HostFrame.albedoTexture", f,
            [](const FormatFacts& k) { return k.renderable && !k.integer && k.channels >= 3; },
            "a colour format of three or more channels (RGBA8, SRGB8_ALPHA8)");
        if (!p.empty()) return p;
    }
    const bool blend = !coverage && options.path == ProjectorPath::GBufferBlend;
    if (f.roughness.texture != 0 && blend) {
        if (f.roughness.channel < 0 || f.roughness.channel > 3)
            return "HostFrame.roughness.channel: " + std::to_string(f.roughness.channel) +
                   " is not 0, 1, 2 or 3";
        const int channel = f.roughness.channel;
        p = checkTexture(
            f.roughness.texture, "HostFrame.roughness.texture", f,
            [channel](const FormatFacts& k) { return k.renderable && !k.integer && k.channels > channel; },
            "a colour format with that channel");
        if (!p.empty()) return p;
    }
    if (f.objectIdTexture != 0) {
        p = checkTexture(
            f.objectIdTexture, "HostFrame.objectIdTexture", f, [](const FormatFacts& k) { return k.integer; },
            "an unsigned integer format (R8UI)");
        if (!p.empty()) return p;
    }
    return sharedTextureProblem(f, options);
}

HostFrame cameraFrame(const ForwardFrame& f) {
    HostFrame h;
    h.x = f.x;
    h.y = f.y;
    h.width = f.width;
    h.height = f.height;
    h.view = f.view;
    h.projection = f.projection;
    h.eye = f.eye;
    h.depth.clip = f.clip;
    h.depth.reversedZ = f.reversedZ;
    return h;
}

ForwardFrame forwardFrame(const HostFrame& h) {
    ForwardFrame f;
    f.x = h.x;
    f.y = h.y;
    f.width = h.width;
    f.height = h.height;
    f.view = h.view;
    f.projection = h.projection;
    f.eye = h.eye;
    f.clip = h.depth.clip;
    f.reversedZ = h.depth.reversedZ;
    return f;
}

std::string forwardFrameProblem(const ForwardFrame& f) {
    if (f.width <= 0 || f.height <= 0 || f.x < 0 || f.y < 0 || f.width > kMaxForwardSize ||
        f.height > kMaxForwardSize)
        return "ForwardFrame viewport " + std::to_string(f.x) + "," + std::to_string(f.y) + " " +
               std::to_string(f.width) + "x" + std::to_string(f.height) + ": the size must be in [1, " +
               std::to_string(kMaxForwardSize) + "] and the corner not negative";
    return cameraProblem(cameraFrame(f), "ForwardFrame");
}

ContextLimits contextLimits() {
    ContextLimits limits;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &limits.storageBindings);
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &limits.textureUnits);
    return limits;
}

std::string forwardBindingsProblem(const ForwardBindings& b, const ContextLimits& limits) {
    const GLint buffers = limits.storageBindings, units = limits.textureUnits;
    const std::pair<uint32_t, const char*> points[] = {
        {b.decals, "decals"}, {b.tiles, "tiles"}, {b.items, "items"}};
    const std::pair<uint32_t, const char*> textures[] = {{b.albedoUnit, "albedoUnit"},
                                                         {b.normalUnit, "normalUnit"}};
    for (size_t i = 0; i < std::size(points); ++i) {
        if (points[i].first >= uint32_t(buffers))
            return std::string("ForwardBindings.") + points[i].second + ": binding point " +
                   std::to_string(points[i].first) + " is past the context's " + std::to_string(buffers);
        for (size_t j = 0; j < i; ++j)
            if (points[j].first == points[i].first)
                return std::string("ForwardBindings.") + points[i].second + ": the binding point of " +
                       points[j].second;
    }
    for (const auto& [unit, name] : textures)
        if (unit >= uint32_t(units))
            return std::string("ForwardBindings.") + name + ": texture unit " + std::to_string(unit) +
                   " is past the context's " + std::to_string(units);
    if (b.albedoUnit == b.normalUnit) return "ForwardBindings.normalUnit: the texture unit of albedoUnit";
    return {};
}

} // namespace spatter::render_detail
