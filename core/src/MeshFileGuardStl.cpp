// MeshFileGuard for STL. OpenMesh's reader takes a file as binary when its size is 84 bytes plus 50 per
// triangle its header counts, and as ASCII otherwise, so that a binary file with a wrong count loads
// as an ASCII file without facets. In ASCII it takes the three lines after each "outer loop" as
// vertices, whatever they hold: a coordinate that is no number ("nan") reads as 0 and leaves the
// rest of the vertex as it was, and a fourth vertex is ignored. It merges corners through an ordered
// map, which NaN coordinates of a binary file leave without order.

#include "MeshFileGuardFormats.hpp"
#include "MeshFileWords.hpp"
#include "TextLineReader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace spatter::detail {

namespace {

constexpr size_t kStlHeaderBytes = 84, kStlTriangleBytes = 50;

uint32_t littleEndian32(const unsigned char* b) {
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

// Whether the first bytes are text, as an ASCII file's are ("solid name\n facet ...").
bool stlLooksLikeText(const unsigned char* bytes, size_t size) {
    for (size_t i = 0; i < size; ++i)
        if ((bytes[i] < 0x20 && !isWordSpace(char(bytes[i]))) || bytes[i] >= 0x7f) return false;
    return true;
}

std::string stlCorner(const float* v) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v[0]), double(v[1]), double(v[2]));
    return text;
}

Status checkBinaryStl(std::istream& in, uint32_t triangles) {
    std::vector<unsigned char> block(kStlTriangleBytes * 4096);
    for (uint32_t first = 0; first < triangles;) {
        const uint32_t count =
            std::min<uint32_t>(triangles - first, uint32_t(block.size() / kStlTriangleBytes));
        if (!in.read(reinterpret_cast<char*>(block.data()), std::streamsize(count * kStlTriangleBytes)))
            return fail("binary STL ends before its triangles do");
        for (uint32_t t = 0; t < count; ++t) {
            float v[9]; // the corners after the facet normal
            std::memcpy(v, block.data() + t * kStlTriangleBytes + 12, sizeof v);
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(v[3 * c]) || !std::isfinite(v[3 * c + 1]) || !std::isfinite(v[3 * c + 2]))
                    return fail("binary STL triangle " + std::to_string(first + t) + ": corner " +
                                std::to_string(c) + " " + stlCorner(v + 3 * c) + " is not finite");
        }
        first += count;
    }
    return {};
}

bool isVertexWord(std::string_view word) {
    static const char kVertex[] = "vertex";
    if (word.size() != 6) return false;
    for (size_t i = 0; i < 6; ++i)
        if ((word[i] | 0x20) != kVertex[i]) return false;
    return true;
}

Status checkStlVertexLine(std::string_view line, size_t number) {
    const std::string at = "line " + std::to_string(number) + ": ";
    std::string_view rest = trimLine(line);
    const std::string_view keyword = nextWord(rest);
    if (!isVertexWord(keyword))
        return fail(at + "facet has fewer than 3 vertices ('" + excerpt(trimLine(line)) +
                    "' where a vertex line belongs)");
    for (int k = 0; k < 3; ++k) {
        const std::string_view word = nextWord(rest);
        float value = 0.0f;
        if (word.empty()) return fail(at + "vertex has " + std::to_string(k) + " coordinates, 3 needed");
        if (const NumberWord kind = readFloatWord(word, value); kind != NumberWord::Finite)
            return fail(at + "vertex coordinate '" + excerpt(word) + "' " + numberWordProblem(kind));
    }
    return {};
}

Status checkAsciiStl(std::istream& in) {
    TextLineReader lines(in);
    int vertexLinesDue = 0; // the reader takes the 3 lines after "outer loop" as vertices
    bool afterFacet = false;
    for (std::string_view line; lines.next(line);) {
        if (vertexLinesDue > 0) {
            if (Status s = checkStlVertexLine(line, lines.lineNumber()); !s) return s;
            afterFacet = --vertexLinesDue == 0;
            continue;
        }
        std::string_view rest = trimLine(line);
        if (afterFacet && isVertexWord(nextWord(rest)))
            return fail("line " + std::to_string(lines.lineNumber()) +
                        ": facet has more than 3 vertices (the reader keeps the first 3)");
        afterFacet = false;
        if (line.find("outer") != std::string_view::npos || line.find("OUTER") != std::string_view::npos)
            vertexLinesDue = 3;
    }
    if (vertexLinesDue > 0) return fail("ASCII STL ends inside a facet (truncated)");
    return {};
}

} // namespace

Status checkStlForOpenMesh(std::ifstream& in, uintmax_t fileSize) {
    unsigned char head[kStlHeaderBytes] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const size_t got = size_t(in.gcount());
    const uint32_t triangles = got == kStlHeaderBytes ? littleEndian32(head + 80) : 0;
    if (got == kStlHeaderBytes && kStlHeaderBytes + kStlTriangleBytes * uintmax_t(triangles) == fileSize)
        return checkBinaryStl(in, triangles);
    if (!stlLooksLikeText(head, got)) {
        if (got < kStlHeaderBytes) return fail("binary STL shorter than its 84-byte header");
        return fail("binary STL: the header counts " + std::to_string(triangles) +
                    (triangles == 1 ? " triangle, which takes " : " triangles, which take ") +
                    std::to_string(kStlHeaderBytes + kStlTriangleBytes * uintmax_t(triangles)) +
                    " bytes, but the file has " + std::to_string(fileSize));
    }
    in.clear();
    in.seekg(0);
    return checkAsciiStl(in);
}

} // namespace spatter::detail
