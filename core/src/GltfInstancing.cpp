#include "GltfInstancing.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <optional>

namespace spatter::gltf {

namespace {

constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";

// The accessor of attribute `name`, viewed as `type`; an absent view when the extension lacks it.
Result<AccessorView> instanceAttribute(const tinygltf::Model& model, const tinygltf::Value& attributes,
                                       const char* name, int type) {
    if (!attributes.Has(name)) return AccessorView{};
    const tinygltf::Value& id = attributes.Get(name);
    const double index = id.IsNumber() ? id.GetNumberAsDouble() : -1.0;
    if (!(index >= 0.0 && index < double(model.accessors.size())))
        return fail(std::string("instance ") + name + " refers to an accessor that does not exist");
    const std::string role = std::string("instance ") + name;
    return viewAccessor(model, int(index), role.c_str(), type, kVertexTypes);
}

// Instance `i`'s transform from the attributes that are present.
Result<glm::dmat4> instanceMatrix(const AccessorView& t, const AccessorView& r, const AccessorView& s,
                                  size_t i) {
    glm::dmat4 m(1.0);
    if (t.present) {
        const glm::vec3 v = t.vec<3>(i);
        if (!finite(v)) return fail("instance " + num(i) + " has a translation that is not finite");
        m = glm::translate(m, glm::dvec3(v));
    }
    if (r.present) {
        const glm::vec4 q = r.vec<4>(i);
        const double length = glm::length(glm::dvec4(q));
        if (!finite(q) || !(length > 1e-12))
            return fail("instance " + num(i) + " has a rotation that is zero or not finite");
        m = m * glm::mat4_cast(glm::dquat(q.w / length, q.x / length, q.y / length, q.z / length));
    }
    if (s.present) {
        const glm::vec3 v = s.vec<3>(i);
        if (!finite(v)) return fail("instance " + num(i) + " has a scale that is not finite");
        m = glm::scale(m, glm::dvec3(v));
    }
    return m;
}

} // namespace

Result<std::optional<std::vector<glm::dmat4>>> instanceTransforms(const tinygltf::Model& model,
                                                                  const tinygltf::Node& node) {
    const tinygltf::Value* ext = findExtension(node.extensions, kInstancing);
    if (!ext) return std::optional<std::vector<glm::dmat4>>();
    if (!ext->Has("attributes") || !ext->Get("attributes").IsObject())
        return fail(std::string("has ") + kInstancing + " without \"attributes\"");
    const tinygltf::Value& attributes = ext->Get("attributes");
    Result<AccessorView> t = instanceAttribute(model, attributes, "TRANSLATION", TINYGLTF_TYPE_VEC3);
    if (!t) return fail(t.error());
    Result<AccessorView> r = instanceAttribute(model, attributes, "ROTATION", TINYGLTF_TYPE_VEC4);
    if (!r) return fail(r.error());
    Result<AccessorView> s = instanceAttribute(model, attributes, "SCALE", TINYGLTF_TYPE_VEC3);
    if (!s) return fail(s.error());
    std::optional<size_t> count;
    for (const AccessorView* v : {&t.value(), &r.value(), &s.value()}) {
        if (!v->present) continue;
        if (count && *count != v->count)
            return fail("has instance attributes of " + num(*count) + " and " + num(v->count) + " elements");
        count = v->count;
    }
    if (!count) return fail(std::string("has ") + kInstancing + " without TRANSLATION, ROTATION or SCALE");
    if (*count > kMaxInstances)
        return fail("has " + num(*count) + " instances, more than the limit of " + num(kMaxInstances));
    std::vector<glm::dmat4> out;
    out.reserve(*count);
    for (size_t i = 0; i < *count; ++i) {
        Result<glm::dmat4> m = instanceMatrix(t.value(), r.value(), s.value(), i);
        if (!m) return fail(m.error());
        out.push_back(m.value());
    }
    return std::optional<std::vector<glm::dmat4>>(std::move(out));
}

} // namespace spatter::gltf
