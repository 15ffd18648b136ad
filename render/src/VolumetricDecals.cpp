#include "VolumetricDecals.hpp"

#include "RendererShaders.hpp"
#include "ShaderProgram.hpp"

#include "spatter/core/CraterMesh.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace spatter::render_detail {

namespace {

struct CraterVertex {
    glm::vec3 position;
    glm::vec3 normal;
};

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// One record per crater (shaders/crater.glsl, std430).
struct CraterRecord {
    glm::mat4 model;
    glm::mat4 normal;
    glm::vec4 plane;
    glm::vec4 clips[2];
    float tolerance = 0.0f;
    float cosAngle = 0.0f;
    float depth = 0.0f;
    uint32_t id = 0;
};
static_assert(sizeof(CraterRecord) == 192, "CraterRecord must match shaders/crater.glsl");

constexpr GLint kBase = 0;                               // uniform: the draw's first record (crater.vert)
constexpr GLuint kRecordSlot = 5;                        // shader storage binding of the records
constexpr int kGroups = 2 * VolumetricDecals::kVariants; // by variant and winding

GlTexture makeCopy(GLenum format, int width, int height) {
    GlTexture t = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, format, width, height);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

} // namespace

Status VolumetricDecals::create() {
    std::vector<CraterVertex> vertices;
    std::vector<uint32_t> indices;
    const CraterShape shape;
    for (int v = 0; v < kVariants; ++v) {
        Result<Mesh> crater = makeCraterMesh(uint32_t(v), shape);
        if (!crater) return fail("volumetric decals: " + crater.error());
        const Mesh& m = crater.value();
        const uint32_t base = uint32_t(vertices.size());
        Variant& out = variants_[v];
        for (size_t i = 0; i < m.positions.size(); ++i) {
            vertices.push_back({m.positions[i], m.normals[i]});
            out.depth = std::max(out.depth, -m.positions[i].z);
        }
        out.firstIndex = uint32_t(indices.size());
        for (uint32_t i : m.indices)
            indices.push_back(base + i);
        out.indexCount = uint32_t(m.indices.size());
        // Footprint: a fan over the rim (the first `segments` vertices, all at z = 0) around the
        // origin; the chipped rim is star-shaped about it.
        const uint32_t centre = uint32_t(vertices.size());
        vertices.push_back({glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)});
        out.footprintFirst = uint32_t(indices.size());
        const uint32_t n = uint32_t(shape.segments);
        for (uint32_t i = 0; i < n; ++i)
            indices.insert(indices.end(), {centre, base + i, base + (i + 1) % n});
        out.footprintCount = 3 * n;
    }
    vertices_ = createBuffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(vertices.size() * sizeof(CraterVertex)), vertices.data(),
                         0);
    indices_ = createBuffer();
    glNamedBufferStorage(indices_.get(), GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    vao_ = createVertexArray();
    const GLuint vao = vao_.get();
    glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(CraterVertex));
    glVertexArrayElementBuffer(vao, indices_.get());
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(CraterVertex, position));
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(CraterVertex, normal));
    glVertexArrayAttribBinding(vao, 1, 0);

    const std::vector<ShaderStage> mark = {{GL_VERTEX_SHADER, "crater.vert"},
                                           {GL_FRAGMENT_SHADER, "crater_mark.frag"}};
    Result<GlProgram> p = buildProgram(shaderLibrary(kRendererShaders), mark, {});
    if (!p) return fail("volumetric decals: " + p.error());
    markProgram_ = std::move(p.value());
    p = buildProgram(shaderLibrary(kRendererShaders), mark, {"IDS"});
    if (!p) return fail("volumetric decals: " + p.error());
    markIdsProgram_ = std::move(p.value());
    p = buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "crater.vert"}, {GL_FRAGMENT_SHADER, "crater.frag"}}, {});
    if (!p) return fail("volumetric decals: " + p.error());
    craterProgram_ = std::move(p.value());
    return {};
}

void VolumetricDecals::setDecals(const std::vector<Decal>& decals, const std::vector<CraterClips>& clips,
                                 const std::vector<DecalType>& types, size_t objectCount) {
    decals_.clear();
    clips_.clear();
    cosMaxAngle_.clear();
    invalid_ = 0;
    for (size_t i = 0; i < decals.size(); ++i) {
        const Decal& d = decals[i];
        const Frame f = d.frame();
        const bool ok = d.object < objectCount && d.type < types.size() &&
                        std::isfinite(types[d.type].maxAngleDeg) && finite3(d.center) && finite3(f.normal) &&
                        finite3(f.tangent) && finite3(f.bitangent) && std::isfinite(d.size.x) &&
                        std::isfinite(d.size.y) && d.size.x > 0.0f && d.size.y > 0.0f &&
                        std::fabs(glm::length(f.normal) - 1.0f) < 1e-3f &&
                        glm::length(glm::cross(f.tangent, f.bitangent)) > 0.5f;
        if (ok) {
            decals_.push_back(d);
            clips_.push_back(i < clips.size() ? clips[i] : CraterClips{});
            const float angle = std::clamp(types[d.type].maxAngleDeg, 0.0f, 90.0f);
            cosMaxAngle_.push_back(std::cos(glm::radians(angle)));
        } else
            ++invalid_;
    }
}

size_t VolumetricDecals::draw(const GBuffer& gbuffer, GLuint idTexture, bool compareIds, bool coverage,
                              const std::vector<glm::dmat4>& transforms, const glm::dvec3& eye) {
    if (decals_.empty()) return 0;
    const int w = gbuffer.width(), h = gbuffer.height();
    if (w != copyWidth_ || h != copyHeight_) {
        albedoCopy_ = makeCopy(GL_SRGB8_ALPHA8, w, h);
        materialCopy_ = makeCopy(GL_RG8, w, h);
        copyWidth_ = w;
        copyHeight_ = h;
    }
    glCopyImageSubData(gbuffer.albedo(), GL_TEXTURE_2D, 0, 0, 0, 0, albedoCopy_.get(), GL_TEXTURE_2D, 0, 0, 0,
                       0, w, h, 1);
    glCopyImageSubData(gbuffer.material(), GL_TEXTURE_2D, 0, 0, 0, 0, materialCopy_.get(), GL_TEXTURE_2D, 0,
                       0, 0, 0, w, h, 1);

    // Records grouped by variant and winding (a mirrored transform turns the crater inside out).
    std::vector<CraterRecord> groups[kGroups];
    const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -eye);
    for (size_t k = 0; k < decals_.size(); ++k) {
        const Decal& d = decals_[k];
        const glm::dmat4 rel = toEye * transforms[d.object] * craterToObject(d);
        const glm::dmat3 m3(rel);
        const double det = glm::determinant(m3);
        if (!(std::fabs(det) > 1e-30) || !std::isfinite(det)) continue;
        const int variant = int(d.id % kVariants);
        CraterRecord r;
        r.model = glm::mat4(rel);
        const glm::dmat3 normal = glm::transpose(glm::inverse(m3));
        r.normal = glm::mat4(glm::mat3(normal));
        const glm::dvec3 axis = glm::normalize(normal * glm::dvec3(0.0, 0.0, 1.0));
        r.plane = glm::vec4(glm::vec3(axis), float(glm::dot(axis, glm::dvec3(rel[3]))));
        r.clips[0] = unpackCraterClip(clips_[k].planes[0]);
        r.clips[1] = unpackCraterClip(clips_[k].planes[1]);
        // The footprint and the surface agree on a flat wall; allow a quarter of the radius for
        // curvature and depth precision.
        const double radius = std::max(glm::length(glm::dvec3(rel[0])), glm::length(glm::dvec3(rel[1])));
        r.tolerance = float(0.25 * radius);
        r.cosAngle = cosMaxAngle_[k];
        r.depth = variants_[variant].depth;
        r.id = d.objectId;
        groups[2 * variant + (det < 0.0 ? 1 : 0)].push_back(r);
    }
    std::vector<CraterRecord> records;
    records.reserve(decals_.size());
    GLuint first[kGroups], count[kGroups];
    for (int g = 0; g < kGroups; ++g) {
        first[g] = GLuint(records.size());
        count[g] = GLuint(groups[g].size());
        records.insert(records.end(), groups[g].begin(), groups[g].end());
    }
    if (records.empty()) return 0;
    const size_t bytes = records.size() * sizeof(CraterRecord);
    if (bytes > recordCapacity_) {
        recordCapacity_ = std::max(bytes, 2 * recordCapacity_);
        records_ = createBuffer();
        glNamedBufferStorage(records_.get(), GLsizeiptr(recordCapacity_), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    glNamedBufferSubData(records_.get(), 0, GLsizeiptr(bytes), records.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecordSlot, records_.get());

    glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.framebuffer());
    glBindVertexArray(vao_.get());
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    size_t draws = 0;
    // One instanced draw per group of the index range `first`, `count` of each variant.
    auto drawGroups = [&](uint32_t Variant::*firstIndex, uint32_t Variant::*indexCount) {
        for (int g = 0; g < kGroups; ++g) {
            if (count[g] == 0) continue;
            const Variant& v = variants_[g / 2];
            glFrontFace(g % 2 == 1 ? GL_CW : GL_CCW);
            glUniform1ui(kBase, first[g]);
            glDrawElementsInstanced(
                GL_TRIANGLES, GLsizei(v.*indexCount), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(uintptr_t(v.*firstIndex) * sizeof(uint32_t)),
                GLsizei(count[g]));
            ++draws;
        }
    };

    // Mark: footprints into the stencil, no colour or depth writes.
    const GLenum none[5] = {GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE};
    glDrawBuffers(5, none);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glUseProgram(compareIds ? markIdsProgram_.get() : markProgram_.get());
    glBindTextureUnit(0, gbuffer.depth());
    glBindTextureUnit(1, gbuffer.normal());
    glBindTextureUnit(2, idTexture);
    drawGroups(&Variant::footprintFirst, &Variant::footprintCount);

    // Craters: inside the marked pixels, farther wins.
    const GLenum buffers[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_NONE,
                               GLenum(coverage ? GL_COLOR_ATTACHMENT4 : GL_NONE)};
    glDrawBuffers(5, buffers);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glUseProgram(craterProgram_.get());
    glBindTextureUnit(1, albedoCopy_.get());
    glBindTextureUnit(3, materialCopy_.get());
    drawGroups(&Variant::firstIndex, &Variant::indexCount);

    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glDepthMask(GL_FALSE);
    return draws;
}

} // namespace spatter::render_detail
