// MeshFileGuard for OFF: OpenMesh's reader reserves what the counts say and reads as many faces as
// the count says, each with as many corners as its own count says, without looking for the end of
// the file. It reads a count of -3 as 4294967293; a coordinate that is no number ("nan") fails every
// read after it, so that no face loads; and it skips a face with a corner past the vertices or a
// vertex twice while the other faces load.

#include "MeshFileGuardFormats.hpp"
#include "MeshFileWords.hpp"

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace spatter::detail {

namespace {

struct OffFormat {
    bool texCoords = false, colors = false, normals = false, binary = false;
    bool declined = false;   // not an OFF file to the reader, which leaves it to another
    bool wordsAfter = false; // more on the header line, which the reader ignores (counts, say)
};

OffFormat readOffFormat(const std::string& header) {
    OffFormat f;
    size_t p = 0;
    f.texCoords = header.compare(0, 2, "ST") == 0;
    if (f.texCoords) p += 2;
    f.colors = p < header.size() && header[p] == 'C';
    if (f.colors) ++p;
    f.normals = p < header.size() && header[p] == 'N';
    if (f.normals) ++p;
    f.declined =
        (p < header.size() && (header[p] == '4' || header[p] == 'n')) || header.compare(p, 3, "OFF") != 0;
    f.binary = header.size() >= p + 10 && header.compare(p + 4, 6, "BINARY") == 0;
    std::string_view rest = std::string_view(header).substr(std::min(header.size(), p + (f.binary ? 10 : 3)));
    f.wordsAfter = !nextWord(rest).empty();
    return f;
}

const char* const kOffTruncated = "OFF data ends before its faces do (truncated or malformed)";

using OffBody = MeshBody<OffFormat>;

// A count or index: binary, 32 bits little-endian; text, a whole integer word. `what` names it for a
// message when it is no integer.
Status readOffInteger(OffBody& b, const std::string& what, int64_t& value) {
    if (b.format.binary) {
        unsigned char c[4];
        if (!b.in.read(reinterpret_cast<char*>(c), 4)) return fail(kOffTruncated);
        value = int64_t(c[0]) | int64_t(c[1]) << 8 | int64_t(c[2]) << 16 | int64_t(c[3]) << 24;
        return {};
    }
    if (!(b.in >> b.word)) return fail(kOffTruncated);
    if (!readIntegerWord(b.word, value)) return fail(what + ": '" + excerpt(b.word) + "' is not an integer");
    return {};
}

Status checkOffCount(const char* what, const char* plural, int64_t count, uintmax_t fileSize) {
    if (count < 0)
        return fail(std::string("OFF header: the ") + what + " count " + std::to_string(count) +
                    " is negative (the reader would take it as " + std::to_string(uint32_t(count)) +
                    ", more than the file has bytes)");
    if (uintmax_t(count) > fileSize)
        return fail(std::string("OFF header: ") + std::to_string(count) + " " + plural +
                    ", more than the file has bytes");
    return {};
}

Status checkOffVertices(OffBody& b) {
    if (b.format.binary) {
        const std::streamoff perVertex =
            12 + (b.format.normals ? 12 : 0) + (b.format.colors ? 12 : 0) + (b.format.texCoords ? 8 : 0);
        b.in.ignore(std::streamsize(perVertex) * b.vertices);
        return {};
    }
    const int numbers = b.format.normals ? 6 : 3;
    for (int64_t i = 0; i < b.vertices; ++i) {
        for (int k = 0; k < numbers; ++k) {
            float value = 0.0f;
            if (!(b.in >> b.word)) return fail(kOffTruncated);
            if (const NumberWord kind = readFloatWord(b.word, value); kind != NumberWord::Finite)
                return fail("OFF vertex " + std::to_string(i) + ": " + (k < 3 ? "coordinate '" : "normal '") +
                            excerpt(b.word) + "' " + numberWordProblem(kind));
        }
        std::getline(b.in, b.word); // the rest of the line: colours, texture coordinates
    }
    return {};
}

// The reader skips a face with fewer than three corners, a corner that is no vertex, or a vertex twice:
// an error unless the face has no area (fewer than three different vertices), which loses no surface.
Status checkOffFace(OffBody& b, int64_t face) {
    const std::string name = "OFF face " + std::to_string(face);
    int64_t count = 0;
    if (Status s = readOffInteger(b, name + " corner count", count); !s) return s;
    if (count < 3 || count > int64_t(kMaxFaceCorners))
        return fail(name + " has " + std::to_string(count) + " corners (at least 3, at most " +
                    std::to_string(kMaxFaceCorners) + ")");
    b.corners.clear();
    for (int64_t k = 0; k < count; ++k) {
        int64_t index = 0;
        if (Status s = readOffInteger(b, name + " corner", index); !s) return s;
        if (index < 0 || index >= b.vertices)
            return fail(name + ": corner " + std::to_string(index) + " is not one of the " +
                        std::to_string(b.vertices) + " vertices (numbered from 0)");
        b.corners.push_back(index);
    }
    if (b.format.colors && !b.format.binary) std::getline(b.in, b.word);
    if (const std::optional<int64_t> twice = vertexTwiceInAFaceWithArea(b.corners))
        return fail(name + " names vertex " + std::to_string(*twice) + " twice");
    return {};
}

} // namespace

Status checkOffForOpenMesh(std::ifstream& in, uintmax_t fileSize) {
    std::string header;
    std::getline(in, header);
    const OffFormat format = readOffFormat(header);
    if (format.declined) return {};
    if (format.wordsAfter)
        return fail("OFF header: the reader ignores the rest of the line '" + excerpt(header) +
                    "'; the counts belong on the next line");
    OffBody b(in, format);
    int64_t faces = 0, edges = 0;
    for (int64_t* count : {&b.vertices, &faces, &edges})
        if (!readOffInteger(b, "OFF header", *count)) return fail("OFF header: no counts");
    if (Status s = checkOffCount("vertex", "vertices", b.vertices, fileSize); !s) return s;
    if (Status s = checkOffCount("face", "faces", faces, fileSize); !s) return s;
    if (Status s = checkOffVertices(b); !s) return s;
    for (int64_t i = 0; i < faces; ++i)
        if (Status s = checkOffFace(b, i); !s) return s;
    return {};
}

} // namespace spatter::detail
