#include "SceneGpu.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace spatter::render_detail {

namespace {

// Interleaved vertex: position, normal, uv, tangent.
struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;
};
static_assert(sizeof(Vertex) == 48, "tightly packed vertex");

GlTexture uploadImage(const Image& image, bool srgb) {
    GlTexture t = createTexture(GL_TEXTURE_2D);
    const int levels = 1 + int(std::floor(std::log2(double(std::max(image.width, image.height)))));
    glTextureStorage2D(t.get(), levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Image rows start at the top; glTF UVs have v = 0 at the top too, so rows go in as they are.
    glTextureSubImage2D(t.get(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.rgba.data());
    glGenerateTextureMipmap(t.get());
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

// A storage buffer holding `data` (one placeholder byte when empty, so that it can be bound).
template <typename T> GlBuffer storageBuffer(const std::vector<T>& data) {
    GlBuffer b = createBuffer();
    glNamedBufferStorage(b.get(), GLsizeiptr(std::max<size_t>(1, data.size() * sizeof(T))),
                         data.empty() ? nullptr : data.data(), 0);
    return b;
}

// Morph deltas of `object` appended to `out`: per target, per vertex, its position, normal and
// tangent deltas (zero where the target has none).
void appendMorphDeltas(const SceneObject& object, std::vector<glm::vec4>& out) {
    const size_t vertices = object.mesh->positions.size();
    for (const MorphTarget& t : object.morphTargets)
        for (size_t v = 0; v < vertices; ++v) {
            out.emplace_back(t.positions[v], 0.0f);
            out.emplace_back(v < t.normals.size() ? t.normals[v] : glm::vec3(0.0f), 0.0f);
            out.emplace_back(v < t.tangents.size() ? t.tangents[v] : glm::vec3(0.0f), 0.0f);
        }
}

// One render mesh's vertices (interleaved, tangents computed where the mesh has none), indices and
// submeshes on the GPU.
GpuMesh uploadMesh(const Mesh& m, uint32_t defaultMaterial) {
    std::vector<glm::vec4> tangents = m.tangents;
    if (tangents.size() != m.positions.size()) {
        Mesh copy = m;
        computeTangents(copy);
        tangents = std::move(copy.tangents);
    }
    std::vector<Vertex> vertices(m.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i) {
        vertices[i].position = m.positions[i];
        vertices[i].normal = i < m.normals.size() ? m.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
        vertices[i].uv = i < m.uvs.size() ? m.uvs[i] : glm::vec2(0.0f);
        vertices[i].tangent = i < tangents.size() ? tangents[i] : glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    }
    GpuMesh g;
    g.vao = createVertexArray();
    g.vertices = createBuffer();
    g.indices = createBuffer();
    glNamedBufferStorage(g.vertices.get(), GLsizeiptr(std::max<size_t>(1, vertices.size()) * sizeof(Vertex)),
                         vertices.empty() ? nullptr : vertices.data(),
                         vertices.empty() ? GL_DYNAMIC_STORAGE_BIT : 0);
    glNamedBufferStorage(
        g.indices.get(), GLsizeiptr(std::max<size_t>(1, m.indices.size()) * sizeof(uint32_t)),
        m.indices.empty() ? nullptr : m.indices.data(), m.indices.empty() ? GL_DYNAMIC_STORAGE_BIT : 0);
    const GLuint vao = g.vao.get();
    glVertexArrayVertexBuffer(vao, 0, g.vertices.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, g.indices.get());
    const GLuint offsets[4] = {offsetof(Vertex, position), offsetof(Vertex, normal), offsetof(Vertex, uv),
                               offsetof(Vertex, tangent)};
    const GLint sizes[4] = {3, 3, 2, 4};
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    if (m.submeshes.empty()) {
        g.submeshes.push_back({0, uint32_t(m.indices.size()), defaultMaterial});
    } else {
        for (const Submesh& s : m.submeshes)
            g.submeshes.push_back(
                {s.firstIndex, s.indexCount, s.material < 0 ? defaultMaterial : uint32_t(s.material)});
    }
    g.triangles = m.triangleCount();
    return g;
}

// Whether `a` and `b` draw the same: every attribute, index and submesh equal.
bool sameMesh(const Mesh& a, const Mesh& b) {
    auto sameSubmesh = [](const Submesh& x, const Submesh& y) {
        return x.firstIndex == y.firstIndex && x.indexCount == y.indexCount && x.material == y.material;
    };
    if (&a == &b) return true; // one mesh that objects share
    return a.positions == b.positions && a.indices == b.indices && a.normals == b.normals && a.uvs == b.uvs &&
           a.tangents == b.tangents &&
           std::equal(a.submeshes.begin(), a.submeshes.end(), b.submeshes.begin(), b.submeshes.end(),
                      sameSubmesh);
}

} // namespace

void SceneGpu::uploadPose(const Scene& scene) {
    firstJoint_.clear();
    jointCount_ = 0;
    for (const Skin& skin : scene.animation.skins) {
        firstJoint_.push_back(uint32_t(jointCount_));
        jointCount_ += skin.joints.size();
    }
    firstWeight_.clear();
    weightCount_ = 0;
    std::vector<PoseObjectGpu> objects;
    std::vector<InfluenceGpu> influences;
    std::vector<glm::vec4> deltas;
    for (const SceneObject& o : scene.objects) {
        PoseObjectGpu p{};
        if (o.skin >= 0 && o.skinWeights.influences > 0) {
            p.skin = glm::uvec4(uint32_t(influences.size()), uint32_t(o.skinWeights.influences),
                                firstJoint_[size_t(o.skin)], 0u);
            for (size_t i = 0; i < o.skinWeights.joints.size(); ++i)
                influences.push_back({o.skinWeights.joints[i], float(o.skinWeights.weights[i])});
        }
        p.morph = glm::uvec4(uint32_t(deltas.size()), uint32_t(o.morphTargets.size()), uint32_t(weightCount_),
                             uint32_t(o.mesh->positions.size()));
        appendMorphDeltas(o, deltas);
        firstWeight_.push_back(uint32_t(weightCount_));
        weightCount_ += o.morphTargets.size();
        objects.push_back(p);
    }
    poseObjects_ = storageBuffer(objects);
    influences_ = storageBuffer(influences);
    morphDeltas_ = storageBuffer(deltas);
}

Status SceneGpu::upload(const Scene& scene) {
    if (Status s = validateScene(scene); !s) return fail("renderer: " + s.error());
    meshes_.clear();
    meshOf_.clear();
    textures_.clear();
    baseTextures_.assign(scene.materials.size(), 0);
    normalTextures_.assign(scene.materials.size(), 0);
    const uint32_t defaultMaterial = uint32_t(scene.materials.size());

    // Objects placed with the same mesh (a level's props, glTF instances) share its upload. The objects
    // whose meshes were uploaded, by their meshes' sizes:
    std::map<std::pair<size_t, size_t>, std::vector<size_t>> uploadedBySize;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Mesh& m = *scene.objects[i].mesh;
        std::vector<size_t>& same = uploadedBySize[{m.positions.size(), m.indices.size()}];
        const auto it = std::find_if(same.begin(), same.end(),
                                     [&](size_t j) { return sameMesh(*scene.objects[j].mesh, m); });
        if (it != same.end()) {
            meshOf_.push_back(meshOf_[*it]);
            continue;
        }
        same.push_back(i);
        meshOf_.push_back(uint32_t(meshes_.size()));
        meshes_.push_back(uploadMesh(m, defaultMaterial));
    }

    // Textures: one per (image, colour space) that some material uses.
    std::map<std::pair<int, bool>, GLuint> uploaded;
    auto texture = [&](int image, bool srgb) -> GLuint {
        if (image < 0) return 0;
        auto it = uploaded.find({image, srgb});
        if (it != uploaded.end()) return it->second;
        textures_.push_back(uploadImage(scene.images[size_t(image)], srgb));
        return uploaded[{image, srgb}] = textures_.back().get();
    };
    std::vector<MaterialGpu> materials(scene.materials.size() + 1);
    for (size_t i = 0; i <= scene.materials.size(); ++i) {
        const Material m = i < scene.materials.size() ? scene.materials[i] : Material{};
        const Material fallback;
        auto finite = [](float v) { return std::isfinite(v); };
        const glm::vec4& c = m.baseColorFactor;
        MaterialGpu& g = materials[i];
        // Non-finite factors (validateScene does not check them) fall back to the defaults.
        g.baseColor = finite(c.x) && finite(c.y) && finite(c.z) && finite(c.w) ? c : fallback.baseColorFactor;
        g.params = glm::vec4(finite(m.roughness) ? m.roughness : fallback.roughness,
                             finite(m.metallic) ? m.metallic : fallback.metallic,
                             finite(m.normalScale) ? m.normalScale : fallback.normalScale, 0.0f);
        if (i < scene.materials.size()) {
            baseTextures_[i] = texture(m.baseColorTexture, true);
            normalTextures_[i] = texture(m.normalTexture, false);
        }
        g.flags = glm::uvec4(i < baseTextures_.size() && baseTextures_[i] ? 1u : 0u,
                             i < normalTextures_.size() && normalTextures_[i] ? 1u : 0u, 0u, 0u);
    }
    materialBuffer_ = createBuffer();
    glNamedBufferStorage(materialBuffer_.get(), GLsizeiptr(materials.size() * sizeof(MaterialGpu)),
                         materials.data(), 0);
    uploadPose(scene);
    return {};
}

} // namespace spatter::render_detail
