#include "GltfRequired.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>

namespace spatter::gltf {

namespace {

using json = nlohmann::json;

// The required properties of each element of a top-level array.
struct Rule {
    const char* array;
    const char* kind; // how a message names an element
    std::initializer_list<const char*> required;
};

// "`what` lacks the required property "<name>"" for the first of `required` that `object` lacks, or "".
std::string lacking(const json& object, const std::string& what,
                    std::initializer_list<const char*> required) {
    if (!object.is_object()) return "";
    for (const char* name : required)
        if (!object.contains(name)) return what + " lacks the required property \"" + name + "\"";
    return "";
}

std::string checkArray(const json& doc, const char* array, const char* kind,
                       std::initializer_list<const char*> required) {
    if (!doc.contains(array) || !doc[array].is_array()) return "";
    const json& items = doc[array];
    for (size_t i = 0; i < items.size(); ++i)
        if (std::string m = lacking(items[i], std::string(kind) + " " + std::to_string(i), required);
            !m.empty())
            return m;
    return "";
}

// Required properties of the objects inside each element of `array`'s `sub` array.
std::string checkNested(const json& doc, const char* array, const char* kind, const char* sub,
                        const char* subKind, std::initializer_list<const char*> required) {
    if (!doc.contains(array) || !doc[array].is_array()) return "";
    const json& items = doc[array];
    for (size_t i = 0; i < items.size(); ++i) {
        if (!items[i].is_object() || !items[i].contains(sub) || !items[i][sub].is_array()) continue;
        const json& subs = items[i][sub];
        for (size_t j = 0; j < subs.size(); ++j) {
            const std::string what =
                std::string(kind) + " " + std::to_string(i) + " " + subKind + " " + std::to_string(j);
            if (std::string m = lacking(subs[j], what, required); !m.empty()) return m;
        }
    }
    return "";
}

} // namespace

std::string missingRequiredProperty(const char* text, size_t size) {
    const json doc = json::parse(text, text + size, nullptr, false);
    if (!doc.is_object()) return "";
    if (std::string m = lacking(doc, "the document", {"asset"}); !m.empty()) return m;
    if (std::string m = lacking(doc["asset"], "the asset", {"version"}); !m.empty()) return m;
    const Rule arrays[] = {{"accessors", "accessor", {"componentType", "count", "type"}},
                           {"animations", "animation", {"channels", "samplers"}},
                           {"buffers", "buffer", {"byteLength"}},
                           {"bufferViews", "buffer view", {"buffer", "byteLength"}},
                           {"cameras", "camera", {"type"}},
                           {"meshes", "mesh", {"primitives"}},
                           {"skins", "skin", {"joints"}}};
    for (const Rule& r : arrays)
        if (std::string m = checkArray(doc, r.array, r.kind, r.required); !m.empty()) return m;
    if (std::string m =
            checkNested(doc, "animations", "animation", "channels", "channel", {"sampler", "target"});
        !m.empty())
        return m;
    if (std::string m =
            checkNested(doc, "animations", "animation", "samplers", "sampler", {"input", "output"});
        !m.empty())
        return m;
    return checkNested(doc, "meshes", "mesh", "primitives", "primitive", {"attributes"});
}

std::string bufferWithoutUri(const char* text, size_t size) {
    const json doc = json::parse(text, text + size, nullptr, false);
    if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return "";
    const json& buffers = doc["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i)
        if (buffers[i].is_object() && !buffers[i].contains("uri"))
            return "buffer " + std::to_string(i) + " has no uri and the file is not a .glb";
    return "";
}

} // namespace spatter::gltf
