#include "GltfPrepare.hpp"

#include "GltfExtension.hpp"
#include "GltfMeshopt.hpp"

#include <nlohmann/json.hpp>

#include <string_view>

namespace spatter::gltf {

namespace {

using json = nlohmann::json;

// Where prepareJson keeps a primitive's indices that tinygltf would refuse.
constexpr const char* kMovedIndices = "SPATTER_moved_indices";

bool hasBufferView(const json& doc, const json& accessor) {
    if (!accessor.is_number_integer() || !doc.contains("accessors") || !doc["accessors"].is_array())
        return true;
    const long long i = accessor.get<long long>();
    if (i < 0 || size_t(i) >= doc["accessors"].size()) return true; // tinygltf reports a bad index
    const json& a = doc["accessors"][size_t(i)];
    return !a.is_object() || a.contains("bufferView");
}

// Moves primitive indices without a buffer view into the primitive's extensions; true when any moved.
bool moveBufferlessIndices(json& doc) {
    if (!doc.contains("meshes") || !doc["meshes"].is_array()) return false;
    bool changed = false;
    for (json& mesh : doc["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (json& prim : mesh["primitives"]) {
            if (!prim.is_object() || !prim.contains("indices") || hasBufferView(doc, prim["indices"]))
                continue;
            if (prim.contains("extensions") && !prim["extensions"].is_object()) continue;
            prim["extensions"][kMovedIndices] = {{"indices", prim["indices"]}};
            prim.erase("indices");
            changed = true;
        }
    }
    return changed;
}

} // namespace

std::optional<std::string> prepareJson(const char* text, size_t size) {
    const std::string_view view(text, size);
    if (view.find("EXT_meshopt_compression") == std::string_view::npos &&
        view.find("KHR_draco_mesh_compression") == std::string_view::npos &&
        view.find("\"sparse\"") == std::string_view::npos)
        return std::nullopt;
    json doc = json::parse(view.begin(), view.end(), nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return std::nullopt;
    const bool placeholders = addMeshoptPlaceholders(doc);
    const bool moved = moveBufferlessIndices(doc);
    if (!placeholders && !moved) return std::nullopt;
    return doc.dump(-1, ' ', false, json::error_handler_t::replace);
}

void restoreMovedIndices(tinygltf::Model& model) {
    for (tinygltf::Mesh& mesh : model.meshes)
        for (tinygltf::Primitive& prim : mesh.primitives) {
            const tinygltf::Value* moved = findExtension(prim.extensions, kMovedIndices);
            if (!moved) continue;
            const double index = numberField(*moved, "indices", -2.0);
            // An index that is not a whole number in int's range names no accessor: -2 is checked as such.
            prim.indices =
                index >= 0.0 && index < 2147483647.0 && index == double(int(index)) ? int(index) : -2;
            prim.extensions.erase(kMovedIndices);
        }
}

} // namespace spatter::gltf
