#include "MeshFileGuard.hpp"

#include "MeshFileGuardFormats.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

namespace spatter::detail {

Status checkMeshFileForOpenMesh(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) return fail("cannot be opened");
    if (extension == ".obj") return checkObjForOpenMesh(in, path);
    if (extension == ".ply") return checkPlyForOpenMesh(in, size);
    if (extension == ".off") return checkOffForOpenMesh(in, size);
    if (extension == ".stl") return checkStlForOpenMesh(in, size);
    return {};
}

std::optional<int64_t> vertexTwiceInAFaceWithArea(std::vector<int64_t>& corners) {
    std::sort(corners.begin(), corners.end());
    const auto twice = std::adjacent_find(corners.begin(), corners.end());
    if (twice == corners.end()) return std::nullopt;
    const int64_t vertex = *twice;
    const bool area = std::unique(corners.begin(), corners.end()) - corners.begin() >= 3;
    return area ? std::optional<int64_t>(vertex) : std::nullopt;
}

} // namespace spatter::detail
