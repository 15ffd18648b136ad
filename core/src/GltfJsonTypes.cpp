#include "GltfJsonTypes.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace spatter::gltf {

namespace {

using json = nlohmann::json;

enum class JsonKind {
    Index,   // an integer >= 0 written without a fraction: tinygltf takes no other as an index or size
    Indices, // an array of those
    Numbers, // an array of numbers, of `length` of them unless 0
    String,
    Boolean,
    Object,
};

struct PropertyRule {
    const char* name;
    JsonKind kind;
    size_t length = 0;
};

bool isIndex(const json& v) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<long long>() >= 0);
}

bool matches(const json& v, const PropertyRule& rule) {
    switch (rule.kind) {
    case JsonKind::Index:
        return isIndex(v);
    case JsonKind::Indices:
        if (!v.is_array()) return false;
        for (const json& e : v)
            if (!isIndex(e)) return false;
        return true;
    case JsonKind::Numbers:
        if (!v.is_array() || (rule.length != 0 && v.size() != rule.length)) return false;
        for (const json& e : v)
            if (!e.is_number()) return false;
        return true;
    case JsonKind::String:
        return v.is_string();
    case JsonKind::Boolean:
        return v.is_boolean();
    case JsonKind::Object:
        return v.is_object();
    }
    return false;
}

std::string expected(const PropertyRule& rule) {
    switch (rule.kind) {
    case JsonKind::Index:
        return "an integer of at least 0";
    case JsonKind::Indices:
        return "an array of integers of at least 0";
    case JsonKind::Numbers:
        return rule.length != 0 ? "an array of " + std::to_string(rule.length) + " numbers"
                                : "an array of numbers";
    case JsonKind::String:
        return "a string";
    case JsonKind::Boolean:
        return "true or false";
    case JsonKind::Object:
        return "an object";
    }
    return "something else";
}

// The JSON of `v`, cut to 32 characters, printable.
std::string shortJson(const json& v) {
    std::string text = v.dump(-1, ' ', true, json::error_handler_t::replace);
    if (text.size() > 32) text = text.substr(0, 32) + "...";
    return text;
}

// "node 3 (arm)" for element 3 of a collection whose elements are `kind`s.
std::string elementName(const char* kind, size_t index, const json& element) {
    const std::string s = std::string(kind) + " " + std::to_string(index);
    const auto name = element.find("name");
    if (name == element.end() || !name->is_string() || name->get_ref<const std::string&>().empty()) return s;
    return s + " (" + name->get_ref<const std::string&>() + ")";
}

using Rules = std::vector<PropertyRule>;

Status checkProperties(const json& object, const std::string& what, const Rules& rules) {
    for (const PropertyRule& rule : rules) {
        const auto it = object.find(rule.name);
        if (it == object.end() || matches(*it, rule)) continue;
        return fail(what + ": \"" + rule.name + "\" is " + shortJson(*it) + ", not " + expected(rule));
    }
    return {};
}

// Calls check(element, its name) for each object in parent[collection] (when that is an array).
template <class Check>
Status forEachElement(const json& parent, const char* collection, const char* kind, const std::string& prefix,
                      const Check& check) {
    const auto list = parent.find(collection);
    if (list == parent.end() || !list->is_array()) return {};
    for (size_t i = 0; i < list->size(); ++i) {
        const json& element = (*list)[i];
        if (!element.is_object()) continue;
        if (Status s = check(element, prefix + elementName(kind, i, element)); !s) return s;
    }
    return {};
}

Status checkPrimitive(const json& primitive, const std::string& what) {
    static const Rules kRules = {{"indices", JsonKind::Index},
                                 {"material", JsonKind::Index},
                                 {"mode", JsonKind::Index},
                                 {"attributes", JsonKind::Object}};
    if (Status s = checkProperties(primitive, what, kRules); !s) return s;
    const auto attributes = primitive.find("attributes");
    if (attributes == primitive.end()) return {};
    for (const auto& [name, accessor] : attributes->items())
        if (!isIndex(accessor))
            return fail(what + ": attribute \"" + name + "\" is " + shortJson(accessor) + ", not " +
                        expected({"", JsonKind::Index}));
    return {};
}

Status checkMesh(const json& mesh, const std::string& what) {
    if (Status s = checkProperties(mesh, what, {{"weights", JsonKind::Numbers}}); !s) return s;
    return forEachElement(mesh, "primitives", "primitive", what + " ", checkPrimitive);
}

Status checkSampler(const json& sampler, const std::string& what) {
    static const Rules kRules = {
        {"input", JsonKind::Index}, {"output", JsonKind::Index}, {"interpolation", JsonKind::String}};
    return checkProperties(sampler, what, kRules);
}

Status checkChannel(const json& channel, const std::string& what) {
    static const Rules kRules = {{"sampler", JsonKind::Index}, {"target", JsonKind::Object}};
    static const Rules kTargetRules = {{"node", JsonKind::Index}, {"path", JsonKind::String}};
    if (Status s = checkProperties(channel, what, kRules); !s) return s;
    const auto target = channel.find("target");
    return target == channel.end() ? Status() : checkProperties(*target, what + " target", kTargetRules);
}

Status checkAnimation(const json& animation, const std::string& what) {
    if (Status s = forEachElement(animation, "samplers", "sampler", what + " ", checkSampler); !s) return s;
    return forEachElement(animation, "channels", "channel", what + " ", checkChannel);
}

// The collections whose elements have only plain properties to check.
struct CollectionRules {
    const char* collection;
    const char* kind;
    Rules rules;
};

const std::vector<CollectionRules>& plainCollections() {
    using K = JsonKind;
    static const std::vector<CollectionRules> kCollections = {
        {"nodes",
         "node",
         {{"mesh", K::Index},
          {"skin", K::Index},
          {"camera", K::Index},
          {"children", K::Indices},
          {"translation", K::Numbers},
          {"rotation", K::Numbers},
          {"scale", K::Numbers},
          {"matrix", K::Numbers},
          {"weights", K::Numbers}}},
        {"scenes", "scene", {{"nodes", K::Indices}}},
        {"accessors",
         "accessor",
         {{"bufferView", K::Index},
          {"byteOffset", K::Index},
          {"componentType", K::Index},
          {"count", K::Index},
          {"normalized", K::Boolean},
          {"type", K::String},
          {"min", K::Numbers},
          {"max", K::Numbers}}},
        {"bufferViews",
         "buffer view",
         {{"buffer", K::Index},
          {"byteOffset", K::Index},
          {"byteLength", K::Index},
          {"byteStride", K::Index},
          {"target", K::Index}}},
        {"buffers", "buffer", {{"byteLength", K::Index}, {"uri", K::String}}},
        {"skins",
         "skin",
         {{"inverseBindMatrices", K::Index}, {"skeleton", K::Index}, {"joints", K::Indices}}},
        {"textures", "texture", {{"source", K::Index}, {"sampler", K::Index}}},
        {"images", "image", {{"bufferView", K::Index}, {"uri", K::String}, {"mimeType", K::String}}},
    };
    return kCollections;
}

Status checkDocument(const json& doc) {
    if (Status s = checkProperties(doc, "the document", {{"scene", JsonKind::Index}}); !s) return s;
    for (const CollectionRules& c : plainCollections()) {
        auto check = [&c](const json& element, const std::string& what) {
            return checkProperties(element, what, c.rules);
        };
        if (Status s = forEachElement(doc, c.collection, c.kind, "", check); !s) return s;
    }
    if (Status s = forEachElement(doc, "meshes", "mesh", "", checkMesh); !s) return s;
    return forEachElement(doc, "animations", "animation", "", checkAnimation);
}

// `text` with every string longer than kLongString characters emptied: embedded buffers and images
// (data URIs of megabytes) need no reading here, and a scan for quotes skips them far faster than the
// JSON parser reads them.
constexpr size_t kLongString = 4096;
std::string withoutLongStrings(std::string_view text) {
    std::string out;
    size_t from = 0; // the start of what is still to be copied
    for (size_t i = 0; i < text.size();) {
        const size_t open = text.find('"', i);
        if (open == std::string_view::npos) break;
        size_t close = open + 1;
        for (;; ++close) { // the next quote not escaped by an odd number of backslashes
            close = text.find('"', close);
            if (close == std::string_view::npos) return std::string(text); // unterminated: the parser says so
            size_t backslashes = 0;
            while (text[close - 1 - backslashes] == '\\')
                ++backslashes;
            if (backslashes % 2 == 0) break;
        }
        if (close - open - 1 > kLongString) {
            out.append(text, from, open + 1 - from);
            from = close;
        }
        i = close + 1;
    }
    return out.append(text, from, std::string_view::npos);
}

} // namespace

Status checkPropertyTypes(const char* text, size_t size) {
    const json doc = json::parse(withoutLongStrings(std::string_view(text, size)), nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return {};
    return checkDocument(doc);
}

} // namespace spatter::gltf
