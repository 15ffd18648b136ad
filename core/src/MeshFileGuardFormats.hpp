#pragma once
// The format checks of MeshFileGuard, one file each: each reads the file the way OpenMesh's reader
// for that format does and says what that reader would get wrong (without the path).

#include "MeshFileGuard.hpp"

#include <cstdint>
#include <fstream>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace spatter::detail {

Status checkObjForOpenMesh(std::ifstream& in, const std::string& path);
Status checkPlyForOpenMesh(std::ifstream& in, uintmax_t fileSize);
Status checkOffForOpenMesh(std::ifstream& in, uintmax_t fileSize);
Status checkStlForOpenMesh(std::ifstream& in, uintmax_t fileSize);

// The body of a PLY or OFF file as its check walks it, with what the header said of it (`Layout`).
template <class Layout> struct MeshBody {
    MeshBody(std::istream& stream, const Layout& l) : in(stream), format(l) {}

    std::istream& in;
    const Layout& format;
    int64_t vertices = 0;
    std::string word;             // reused from value to value
    std::vector<int64_t> corners; // reused from face to face
};

// The vertex a face of `corners` names twice, where the face still has three different vertices
// (the PLY and OFF readers skip such a face and its surface with it); nothing otherwise: a face of
// fewer has no area and may go. Sorts `corners`.
std::optional<int64_t> vertexTwiceInAFaceWithArea(std::vector<int64_t>& corners);

} // namespace spatter::detail
