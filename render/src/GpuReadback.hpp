#pragma once
// GpuReadback: a few 32-bit values that shaders write into a buffer of its own, read on the CPU once
// the GPU has passed a mark queued after the writes, without a stall unless asked: GpuCulling's
// counts, ForwardBins' left-out flag and fullest tile. The mark is a timestamp query rather than a
// fence: on a GPU a fence sends the commands queued so far on their way, which left the GPU idle
// between the batches (about 7 us a fence at the end of the projector's pass on an H200), where a
// timestamp costs about one.

#include "GlObjects.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

class GpuReadback {
public:
    // Room for `values` 32-bit values; the latest read starts as zeros.
    explicit GpuReadback(size_t values = 1) : latest_(values, 0) {}

    // The buffer the values are read from, for a shader to write them into (bound as a storage buffer).
    GLuint target();
    // Marks the writes queued so far as one read (after a GL_BUFFER_UPDATE_BARRIER_BIT barrier); an
    // earlier read not taken yet is dropped.
    void mark();
    // Drops a read not taken yet, and its values: the latest read becomes zeros, and none has been read.
    void reset();
    // The values of the latest read the GPU has finished (this one's when `wait`).
    const std::vector<uint32_t>& latest(bool wait);
    // The values latest() last gave, without a new look at the mark.
    const std::vector<uint32_t>& values() const { return latest_; }
    // Whether a read has finished since construction or reset(): the values are the GPU's.
    bool hasRead() const { return hasRead_; }

private:
    GlBuffer buffer_;
    GlQuery query_;
    bool pending_ = false; // a mark not taken yet
    std::vector<uint32_t> latest_;
    bool hasRead_ = false;
};

} // namespace spatter::render_detail
