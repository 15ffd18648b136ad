// MeshFileGuard for PLY: OpenMesh's header parser reads word by word until "end_header" and loops
// forever once a read fails; it takes the last element for a "property" even when there is none. The
// body readers take every count from the file (element counts for reserve, a face's corner count for
// the corners read) and fill a face with garbage corners past the end of a binary file.

#include "MeshFileGuardFormats.hpp"
#include "MeshFileWords.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <vector>

namespace spatter::detail {

namespace {

enum class PlyType {
    Unsupported,
    Float32,
    Float64,
    Float,
    Double,
    Int8,
    UInt8,
    Char,
    UChar,
    Int32,
    UInt32,
    Int,
    UInt,
    Int16,
    UInt16,
    Short,
    UShort
};

// The type named by either word, in the reader's order of preference.
PlyType plyType(const std::string& a, const std::string& b) {
    static const std::pair<const char*, PlyType> kNames[] = {
        {"float32", PlyType::Float32}, {"float64", PlyType::Float64}, {"float", PlyType::Float},
        {"double", PlyType::Double},   {"int8", PlyType::Int8},       {"uint8", PlyType::UInt8},
        {"char", PlyType::Char},       {"uchar", PlyType::UChar},     {"int32", PlyType::Int32},
        {"uint32", PlyType::UInt32},   {"int", PlyType::Int},         {"uint", PlyType::UInt},
        {"int16", PlyType::Int16},     {"uint16", PlyType::UInt16},   {"short", PlyType::Short},
        {"ushort", PlyType::UShort}};
    for (const auto& [name, type] : kNames)
        if (a == name || b == name) return type;
    return PlyType::Unsupported;
}

bool isPlyTypeName(const std::string& s) {
    return plyType(s, s) != PlyType::Unsupported;
}

size_t plySize(PlyType t) {
    switch (t) {
    case PlyType::Float64:
    case PlyType::Double:
        return 8;
    case PlyType::Float32:
    case PlyType::Float:
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Int:
    case PlyType::UInt:
        return 4;
    case PlyType::Int16:
    case PlyType::UInt16:
    case PlyType::Short:
    case PlyType::UShort:
        return 2;
    case PlyType::Int8:
    case PlyType::UInt8:
    case PlyType::Char:
    case PlyType::UChar:
        return 1;
    case PlyType::Unsupported:
        break;
    }
    return 0;
}

bool plyFloat(PlyType t) {
    return t == PlyType::Float32 || t == PlyType::Float;
}

bool plyFloatOrDouble(PlyType t) {
    return plyFloat(t) || t == PlyType::Float64 || t == PlyType::Double;
}

// How the reader takes a property from the body.
enum class PlyRead {
    Float,   // a coordinate, normal or texture coordinate (text: a float; binary: float or double)
    Color,   // a colour channel (float for float/float32, an integer otherwise)
    Corners, // the face's vertex_indices list
    Skip,    // anything else (text: one word; binary: the size of its type)
};

struct PlyProperty {
    std::string name;
    PlyRead read = PlyRead::Skip;
    PlyType type = PlyType::Unsupported;
    PlyType countType = PlyType::Unsupported; // Corners: the type of the corner count
};

struct PlyElement {
    std::string name;
    unsigned count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    std::vector<PlyElement> elements;
    bool binary = false, msb = false;
    bool declined = false; // not a PLY file to the reader, which leaves it to another
};

PlyRead plyRead(const std::string& element, const std::string& name) {
    static const char* const kVertexFloats[] = {"x", "y", "z", "nx", "ny", "nz", "u", "s", "v", "t"};
    static const char* const kVertexColors[] = {"red",           "green",        "blue", "diffuse_red",
                                                "diffuse_green", "diffuse_blue", "alpha"};
    static const char* const kFaceColors[] = {"red", "green", "blue", "alpha"};
    auto in = [&](const auto& list) {
        return std::find(std::begin(list), std::end(list), name) != std::end(list);
    };
    if (element == "vertex" && in(kVertexFloats)) return PlyRead::Float;
    if ((element == "vertex" && in(kVertexColors)) || (element == "face" && in(kFaceColors)))
        return PlyRead::Color;
    return PlyRead::Skip;
}

// Reads `size` bytes as an integer of type `t` (endianness `msb`); false past the end of the file.
bool readPlyInteger(std::istream& in, PlyType t, bool msb, int64_t& value) {
    const size_t size = plySize(t);
    unsigned char b[8] = {};
    if (!in.read(reinterpret_cast<char*>(b), std::streamsize(size))) return false;
    if (msb) std::reverse(b, b + size);
    uint64_t u = 0;
    for (size_t i = size; i-- > 0;)
        u = (u << 8) | b[i];
    const bool isSigned = t == PlyType::Int8 || t == PlyType::Char || t == PlyType::Int16 ||
                          t == PlyType::Short || t == PlyType::Int32 || t == PlyType::Int;
    if (isSigned && size < 8 && (u >> (8 * size - 1)) != 0) u |= ~uint64_t(0) << (8 * size);
    value = int64_t(u);
    return true;
}

// Bytes the binary reader consumes for a value of type `t` read as `read` (it skips the read of a
// type it cannot convert).
size_t plyBinaryBytes(PlyRead read, PlyType t) {
    if (read == PlyRead::Float) return plyFloatOrDouble(t) ? plySize(t) : 0;
    if (read == PlyRead::Color) return plyFloat(t) ? 4 : plyFloatOrDouble(t) ? 0 : plySize(t);
    return plySize(t);
}

Status readPlyProperty(std::istream& in, PlyElement& e) {
    std::string first, second, name;
    if (!(in >> first)) return fail("PLY header: incomplete property");
    PlyProperty p;
    if (first == "list") {
        std::string countType, entryType;
        if (!(in >> countType >> entryType >> name)) return fail("PLY header: incomplete list property");
        const bool corners = e.name == "face" && (name == "vertex_index" || name == "vertex_indices");
        if (!corners) // read as one value, the list would shift everything after it
            return fail("PLY header: list property '" + name + "' of element '" + e.name +
                        "' is not supported");
        if (countType != "uint8" && countType != "uint16" && countType != "uchar" && countType != "int")
            return fail("PLY header: list count type '" + countType + "' is not supported");
        p.read = PlyRead::Corners;
        p.countType = plyType(countType, countType);
        p.type = plyType(entryType, entryType);
        if (p.type == PlyType::Unsupported || plyFloatOrDouble(p.type))
            return fail("PLY header: vertex indices of type '" + entryType + "'");
    } else {
        if (!(in >> second)) return fail("PLY header: incomplete property");
        p.type = plyType(first, second);
        name = isPlyTypeName(first) ? second : isPlyTypeName(second) ? first : std::string();
        if (p.type == PlyType::Unsupported)
            return fail("PLY header: property '" + first + " " + second + "' has no supported type");
        p.read = plyRead(e.name, name);
    }
    p.name = name;
    e.properties.push_back(p);
    return {};
}

Status readPlyElement(std::istream& in, uintmax_t fileSize, std::vector<PlyElement>& elements) {
    PlyElement e;
    std::string count;
    int64_t value = 0;
    if (!(in >> e.name >> count) || !readIntegerWord(count, value))
        return fail("PLY header: element without a name and a count");
    if (value < 0 || uintmax_t(value) > fileSize)
        return fail("PLY header: element '" + e.name + "' counts " + excerpt(count) +
                    (value < 0 ? ", a negative count" : ", more than the file has bytes"));
    e.count = unsigned(value);
    for (const PlyElement& other : elements)
        if (other.name == e.name && (e.name == "vertex" || e.name == "face"))
            return fail("PLY header: more than one '" + e.name + "' element");
    elements.push_back(e);
    return {};
}

// Reads the header as the reader does and leaves `in` where the reader starts on the body.
Status readPlyHeader(std::ifstream& in, uintmax_t fileSize, PlyHeader& h) {
    std::string line;
    std::getline(in, line);
    std::string magic; // the first line must be the single word ply (else the reader declines it)
    if (std::istringstream(line) >> magic >> line) magic.clear();
    std::string keyword, format;
    float version = 0.0f;
    h.declined = magic != "ply" && magic != "PLY";
    if (h.declined) return {};
    if (!(in >> keyword >> format >> version)) return fail("PLY header: no format line");
    h.declined = format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian";
    if (h.declined) return {};

    std::streamoff beforeWord = in.tellg();
    while (in >> keyword && keyword != "end_header") {
        Status s;
        if (keyword == "comment") {
            std::getline(in, line);
        } else if (keyword == "element") {
            s = readPlyElement(in, fileSize, h.elements);
        } else if (keyword == "property") {
            if (h.elements.empty()) return fail("PLY header: property before any element");
            s = readPlyProperty(in, h.elements.back());
        }
        if (!s) return s;
        beforeWord = in.tellg();
    }
    if (keyword != "end_header") return fail("PLY header has no end_header (truncated or malformed)");

    h.binary = format != "ascii";
    h.msb = format == "binary_big_endian";
    for (const PlyElement& e : h.elements)
        for (const PlyProperty& p : e.properties)
            if (h.binary && p.read != PlyRead::Corners && plyBinaryBytes(p.read, p.type) == 0)
                return fail("binary PLY: a coordinate or colour of element '" + e.name +
                            "' has a type the reader skips (coordinates: float or double; colours: float or "
                            "an integer type)");
    if (h.binary) { // the reader starts at the word before end_header plus "\nend_header\n" (or CR LF)
        in.clear();
        in.seekg(beforeWord);
        char c1 = 0, c2 = 0;
        in.get(c1);
        in.get(c2);
        in.clear();
        in.seekg(beforeWord + ((c1 == '\r' && c2 == '\n') ? 14 : 12));
    }
    return {};
}

// The body as the reader walks it: element by element, up to and including the faces.
using PlyBody = MeshBody<PlyHeader>;

const char* const kPlyTruncated = "PLY data ends before its faces do (truncated or malformed)";

std::string plyItem(const std::string& element, unsigned i) {
    return "PLY " + element + " " + std::to_string(i);
}

// One value of a text PLY file: a whole word, a finite number where the reader reads a float.
Status checkPlyText(PlyBody& b, const PlyElement& e, const PlyProperty& p, unsigned i) {
    if (!(b.in >> b.word))
        return fail(e.name == "face" ? kPlyTruncated
                                     : "PLY element '" + e.name + "' is truncated or malformed");
    float f = 0.0f;
    int64_t n = 0;
    if (p.read == PlyRead::Float || (p.read == PlyRead::Color && plyFloat(p.type))) {
        if (const NumberWord kind = readFloatWord(b.word, f); kind != NumberWord::Finite)
            return fail(plyItem(e.name, i) + ": " + p.name + " '" + excerpt(b.word) + "' " +
                        numberWordProblem(kind));
    } else if (p.read == PlyRead::Color && !readIntegerWord(b.word, n)) {
        return fail(plyItem(e.name, i) + ": " + p.name + " '" + excerpt(b.word) + "' is not an integer");
    }
    return {};
}

// A face's corner count or index: binary, of type `t`; text, a whole integer word.
Status readPlyIndex(PlyBody& b, PlyType t, unsigned face, int64_t& value) {
    if (b.format.binary)
        return readPlyInteger(b.in, t, b.format.msb, value) ? Status() : Status(fail(kPlyTruncated));
    if (!(b.in >> b.word)) return fail(kPlyTruncated);
    if (!readIntegerWord(b.word, value))
        return fail(plyItem("face", face) + ": '" + excerpt(b.word) + "' is not an integer");
    return {};
}

// The reader skips a face with fewer than three corners, a corner that is no vertex, or a vertex twice:
// an error unless the face has no area (fewer than three different vertices), which loses no surface.
Status checkPlyCorners(PlyBody& b, const PlyProperty& p, unsigned face) {
    int64_t count = 0;
    if (Status s = readPlyIndex(b, p.countType, face, count); !s) return s;
    if (count < 3 || count > int64_t(kMaxFaceCorners))
        return fail(plyItem("face", face) + " has " + std::to_string(count) +
                    " corners (at least 3, at most " + std::to_string(kMaxFaceCorners) + ")");
    b.corners.clear();
    for (int64_t k = 0; k < count; ++k) {
        int64_t index = 0;
        if (Status s = readPlyIndex(b, p.type, face, index); !s) return s;
        if (index < 0 || index >= b.vertices)
            return fail(plyItem("face", face) + ": corner " + std::to_string(index) + " is not one of the " +
                        std::to_string(b.vertices) + " vertices (numbered from 0)");
        b.corners.push_back(index);
    }
    if (const std::optional<int64_t> twice = vertexTwiceInAFaceWithArea(b.corners))
        return fail(plyItem("face", face) + " names vertex " + std::to_string(*twice) + " twice");
    return {};
}

Status checkPlyBody(PlyBody& b) {
    for (const PlyElement& e : b.format.elements) {
        if (e.name == "vertex") b.vertices = e.count;
        for (unsigned i = 0; i < e.count; ++i) {
            for (const PlyProperty& p : e.properties) {
                Status s;
                if (p.read == PlyRead::Corners)
                    s = checkPlyCorners(b, p, i);
                else if (b.format.binary)
                    b.in.ignore(std::streamsize(plyBinaryBytes(p.read, p.type)));
                else
                    s = checkPlyText(b, e, p, i);
                if (!s) return s;
                if (e.name == "face" && b.in.fail()) return fail(kPlyTruncated);
            }
        }
        if (e.name == "face") break; // the reader stops after the faces
        if (b.in.fail()) return fail("PLY element '" + e.name + "' is truncated or malformed");
    }
    return {};
}

} // namespace

Status checkPlyForOpenMesh(std::ifstream& in, uintmax_t fileSize) {
    PlyHeader header;
    if (Status s = readPlyHeader(in, fileSize, header); !s || header.declined) return s;
    PlyBody body(in, header);
    return checkPlyBody(body);
}

} // namespace spatter::detail
