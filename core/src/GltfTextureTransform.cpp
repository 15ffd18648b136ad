#include "GltfTextureTransform.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

#include <cmath>

namespace spatter::gltf {

namespace {

constexpr const char* kTransform = "KHR_texture_transform";

// Field `key` of `ext` as two finite numbers; `fallback` when absent.
Result<glm::dvec2> pairField(const tinygltf::Value& ext, const char* key, glm::dvec2 fallback) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber() ||
        !std::isfinite(v.Get(0).GetNumberAsDouble()) || !std::isfinite(v.Get(1).GetNumberAsDouble()))
        return fail(std::string("\"") + key + "\" is not two numbers");
    return glm::dvec2(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
}

struct Transform {
    glm::dmat3 matrix{1.0};
    int texCoord = 0;
};

// The transform in the extensions of one texture info; no value without the extension.
Result<std::optional<Transform>> readTransform(const tinygltf::ExtensionMap& extensions, int texCoord) {
    const tinygltf::Value* ext = findExtension(extensions, kTransform);
    if (!ext) return std::optional<Transform>();
    if (!ext->IsObject()) return fail(std::string(kTransform) + " is not an object");
    Result<glm::dvec2> offset = pairField(*ext, "offset", glm::dvec2(0.0));
    if (!offset) return fail(std::string(kTransform) + " " + offset.error());
    Result<glm::dvec2> scale = pairField(*ext, "scale", glm::dvec2(1.0));
    if (!scale) return fail(std::string(kTransform) + " " + scale.error());
    const double r = numberField(*ext, "rotation", 0.0);
    const double c = std::cos(r), s = std::sin(r);
    Transform t;
    const glm::dmat3 translation(1, 0, 0, 0, 1, 0, offset->x, offset->y, 1);
    const glm::dmat3 rotation(c, s, 0, -s, c, 0, 0, 0, 1);
    const glm::dmat3 scaling(scale->x, 0, 0, 0, scale->y, 0, 0, 0, 1);
    t.matrix = translation * rotation * scaling;
    t.texCoord = int(numberField(*ext, "texCoord", double(texCoord)));
    return std::optional<Transform>(t);
}

} // namespace

Result<std::optional<glm::dmat3>> materialUvTransform(const tinygltf::Model& model, int material,
                                                      std::string& warning) {
    if (!validIndex(material, model.materials.size())) return std::optional<glm::dmat3>();
    const tinygltf::Material& m = model.materials[size_t(material)];
    const std::string what = named("material", size_t(material), m.name);
    const tinygltf::TextureInfo& base = m.pbrMetallicRoughness.baseColorTexture;
    Result<std::optional<Transform>> b = readTransform(base.extensions, base.texCoord);
    if (!b) return fail(what + ": base colour texture " + b.error());
    Result<std::optional<Transform>> n = readTransform(m.normalTexture.extensions, m.normalTexture.texCoord);
    if (!n) return fail(what + ": normal texture " + n.error());
    const std::optional<Transform>& used = b.value() ? b.value() : n.value();
    if (!used) return std::optional<glm::dmat3>();
    if (b.value() && n.value() && b.value()->matrix != n.value()->matrix)
        warning = what + ": the normal texture's " + kTransform +
                  " differs from the base colour texture's; both use the base colour's";
    if (used->texCoord != 0)
        warning = what + ": " + kTransform + " names texture coordinates " + std::to_string(used->texCoord) +
                  "; TEXCOORD_0 is transformed";
    return std::optional<glm::dmat3>(used->matrix);
}

void transformUvs(const glm::dmat3& transform, std::vector<glm::vec2>& uvs, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
        uvs[i] = glm::vec2(transform * glm::dvec3(glm::dvec2(uvs[i]), 1.0));
}

void transformTangents(const glm::dmat3& transform, const std::vector<glm::vec3>& normals,
                       std::vector<glm::vec4>& tangents, size_t begin, size_t end) {
    const glm::dmat2 a(transform[0][0], transform[0][1], transform[1][0], transform[1][1]);
    const double det = glm::determinant(a);
    if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) return;
    const glm::dmat2 inv = glm::inverse(a); // inv[0]: d(u, v)/du', inv[1]: d(u, v)/dv'
    for (size_t i = begin; i < end; ++i) {
        const glm::dvec3 n(normals[i]), t(tangents[i]);
        if (glm::dot(n, n) == 0.0) continue;
        const glm::dvec3 b = double(tangents[i].w < 0.0f ? -1.0f : 1.0f) * glm::cross(n, t);
        const glm::dvec3 du = t * inv[0][0] + b * inv[0][1];
        const glm::dvec3 dv = t * inv[1][0] + b * inv[1][1];
        const double length = glm::length(du);
        if (!(length > 0.0) || !std::isfinite(length)) continue;
        const double w = glm::dot(glm::cross(n, du), dv) < 0.0 ? -1.0 : 1.0;
        tangents[i] = glm::vec4(glm::vec3(du / length), float(w));
    }
}

} // namespace spatter::gltf
