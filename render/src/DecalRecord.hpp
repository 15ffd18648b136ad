#pragma once
// DecalRecord: a Decal and a DecalType as the GPU keeps them (DecalRecordGpu, DecalTypeGpu in
// GpuLayouts.hpp): 48 bytes per decal, its box and what is its own (44 on the GPU:
// DecalRecordBuffers.hpp), and one entry per type for the rest of its look.

#include "GpuLayouts.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace spatter::render_detail {

// The record of `d`; false (and a record with a zero box but its object and type) when its box is degenerate,
// not finite, without an orientation or too far from its object's origin for its size to be inverted in
// float. The record keeps the decal's packed frame as it is: the shaders unpack it.
bool buildDecalRecord(const Decal& d, DecalRecordGpu& out);

// The type as the shaders read it, with its layer's cutout (`cutouts`: one per texture layer); info.z is 0
// when decals of the type cannot be drawn (a texture layer outside the cutouts, a tint, angle or
// roughness that is not finite).
DecalTypeGpu buildDecalType(const DecalType& t, float wrapMaxAngleDeg, const std::vector<glm::vec4>& cutouts);

// The unit box -> object space transform of a drawable record (the inverse of its rows), in double.
glm::dmat4 recordBoxToObject(const DecalRecordGpu& r);

inline uint16_t recordType(const DecalRecordGpu& r) {
    return uint16_t(r.info.y & 0xffffu);
}
// The record's own DecalFlag bits: kDecalMirrored when its packed frame is mirrored.
inline uint32_t recordFlags(const DecalRecordGpu& r) {
    return packedMirrored(uint64_t(r.frame.y) << 32) ? kDecalMirrored : 0u;
}

} // namespace spatter::render_detail
