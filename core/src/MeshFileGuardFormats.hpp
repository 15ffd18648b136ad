#pragma once
// The format checks of MeshFileGuard, one file each: each reads the file the way OpenMesh's reader
// for that format does and says what that reader would get wrong (without the path).

#include "MeshFileGuard.hpp"

#include <cstdint>
#include <fstream>
#include <string>

namespace spatter::detail {

Status checkObjForOpenMesh(std::ifstream& in, const std::string& path);
Status checkPlyForOpenMesh(std::ifstream& in, uintmax_t fileSize);
Status checkOffForOpenMesh(std::ifstream& in, uintmax_t fileSize);
Status checkStlForOpenMesh(std::ifstream& in, uintmax_t fileSize);

} // namespace spatter::detail
