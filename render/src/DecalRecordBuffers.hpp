#pragma once
// DecalRecordBuffers: the two GPU buffers that hold decal records (DecalRecordGpu) in the form the
// shaders read them (decal_data.glsl): the bounds, 16 bytes a decal, all that the culling's pass over
// every decal reads (its centre, a bounding radius and its object's index, the low 16 bits of it),
// and the bodies, 28 bytes, the rest, which the passes over the decals in view read with the bounds.
// Kept apart, the pass over a million decals reads a third of the bytes it would read from whole
// records.

#include "GlObjects.hpp"
#include "GpuLayouts.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

// The two parts of record `r`. The bounds' radius holds the box (recordRadius) and rounds up; a
// record that cannot be drawn has a radius of 0.
DecalBoundsGpu recordBounds(const DecalRecordGpu& r);
DecalBodyGpu recordBody(const DecalRecordGpu& r);

// Binds a decal set's two buffers at their binding points (kDecalBoundsBuffer, kDecalBuffer).
void bindDecalRecords(GLuint bounds, GLuint bodies);

class DecalRecordBuffers {
public:
    // Room for `count` records (growBuffer: by a quarter, from 64), keeping the first `keep` held.
    void reserve(size_t count, size_t keep);
    // Sends `records` to places [begin, begin + records.size()) (within the room reserved); returns
    // the bytes sent.
    size_t upload(size_t begin, const std::vector<DecalRecordGpu>& records);
    // Buffers sized to hold exactly `records` (one record that cannot be drawn when it is empty).
    void assign(const std::vector<DecalRecordGpu>& records);

    // Both at their binding points (bindDecalRecords).
    void bind() const { bindDecalRecords(bounds(), bodies()); }
    GLuint bounds() const { return bounds_.get(); }
    GLuint bodies() const { return bodies_.get(); }
    size_t bytes() const { return boundsCapacity_ + bodiesCapacity_; }

private:
    GlBuffer bounds_, bodies_;
    size_t boundsCapacity_ = 0, bodiesCapacity_ = 0;
};

} // namespace spatter::render_detail
