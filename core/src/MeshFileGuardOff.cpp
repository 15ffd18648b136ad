// MeshFileGuard for OFF: OpenMesh's reader reserves what the counts say and reads as many faces as
// the count says, each with as many corners as its own count says, without looking for the end of
// the file.

#include "MeshFileGuardFormats.hpp"

#include <fstream>
#include <string>

namespace spatter::detail {

Status checkOffForOpenMesh(std::ifstream& in, uintmax_t fileSize) {
    std::string header;
    std::getline(in, header);
    size_t p = 0;
    const bool texCoords = header.compare(0, 2, "ST") == 0;
    if (texCoords) p += 2;
    const bool colors = p < header.size() && header[p] == 'C';
    if (colors) ++p;
    const bool normals = p < header.size() && header[p] == 'N';
    if (normals) ++p;
    if (p < header.size() && (header[p] == '4' || header[p] == 'n')) return {}; // declined by the reader
    if (header.compare(p, 3, "OFF") != 0) return {};
    const bool binary = header.size() >= p + 10 && header.compare(p + 4, 6, "BINARY") == 0;

    const std::string truncated = "OFF data ends before its faces do (truncated or malformed)";
    unsigned vertices = 0, faces = 0, edges = 0;
    auto readCount = [&](unsigned& value) {
        if (!binary) return bool(in >> value);
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
        value = unsigned(b[0]) | unsigned(b[1]) << 8 | unsigned(b[2]) << 16 | unsigned(b[3]) << 24;
        return true;
    };
    if (!readCount(vertices) || !readCount(faces) || !readCount(edges)) return fail("OFF header: no counts");
    if (vertices > fileSize || faces > fileSize)
        return fail("OFF header: " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                    " faces, more than the file has bytes");
    if (binary) {
        const std::streamoff perVertex = 12 + (normals ? 12 : 0) + (colors ? 12 : 0) + (texCoords ? 8 : 0);
        in.ignore(std::streamsize(perVertex) * vertices);
    } else {
        for (unsigned i = 0; i < vertices && !in.eof(); ++i) {
            float x, y, z;
            in >> x >> y >> z;
            if (normals) in >> x >> y >> z;
            std::string rest;
            std::getline(in, rest);
        }
    }
    for (unsigned i = 0; i < faces; ++i) {
        unsigned corners = 0;
        if (!readCount(corners)) return fail(truncated);
        if (corners > kMaxFaceCorners)
            return fail("OFF face " + std::to_string(i) + " has " + std::to_string(corners) +
                        " corners (at most " + std::to_string(kMaxFaceCorners) + ")");
        for (unsigned k = 0; k < corners; ++k) {
            unsigned index = 0;
            if (!readCount(index)) return fail(truncated);
        }
        if (colors && !binary) {
            std::string rest;
            std::getline(in, rest);
        }
    }
    return {};
}

} // namespace spatter::detail
