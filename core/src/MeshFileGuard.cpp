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

} // namespace spatter::detail
