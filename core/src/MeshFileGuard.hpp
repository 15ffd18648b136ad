#pragma once
// MeshFileGuard: what OpenMesh's OBJ, PLY, OFF and STL readers cannot be trusted with, checked before
// loadMeshFile hands them a file. Those readers take counts and indices from the file unchecked:
// a PLY header that ends early makes the header parser loop forever, a face corner past the
// vertices makes the OBJ reader write out of bounds, and a count of billions makes any of them
// reserve or fill gigabytes; and what they cannot parse they skip, so that a vertex line of "nan"
// shifts every later face onto other vertices. The guard reads the file the way those readers do and
// rejects it where they would go wrong or leave something out; a file it accepts is read by OpenMesh
// as before, whole.

#include "spatter/core/Result.hpp"

#include <string>

namespace spatter::detail {

// The most corners a face may have (OpenMesh checks every pair of a face's corners).
constexpr unsigned kMaxFaceCorners = 4096;

// Checks `path` for the reader its extension selects (.obj, .ply, .off, .stl, case-insensitive;
// other extensions pass). Empty when OpenMesh may read it; otherwise what is wrong, without the path.
Status checkMeshFileForOpenMesh(const std::string& path);

} // namespace spatter::detail
