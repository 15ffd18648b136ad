#pragma once
// KHR_draco_mesh_compression: primitives whose geometry is a Draco bitstream. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

namespace spatter::gltf {

// Decodes, with libdraco, every primitive that has the extension: its attributes named in the
// extension and its triangles become new accessors over new buffers (each in the component type its
// original accessor declares), the primitive refers to them and becomes a triangle list, and the
// extension is removed. Buffer views must have been checked against their buffers. The error names
// the mesh, the primitive and the problem.
Status decodeDracoPrimitives(tinygltf::Model& model);

} // namespace spatter::gltf
