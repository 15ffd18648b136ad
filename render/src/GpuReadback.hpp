#pragma once
// GpuReadback: a few 32-bit values that shaders write into a buffer, read on the CPU once the GPU has
// passed a mark queued after the writes, without a stall unless asked: GpuCulling's counts,
// ForwardBins' left-out flag and fullest tile. The mark is a timestamp query rather than a fence: on
// a GPU a fence sends the commands queued so far on their way, which left the GPU idle between the
// batches (about 7 us a fence at the end of the projector's pass on an H200), where a timestamp costs
// about one. Each read has a buffer of its own in a ring of three, mapped for good, so that reading
// one is a copy from memory the GPU has finished writing: no GL call that could wait for the commands
// queued since (glGetBufferSubData there waited for the whole frame queued before it, 1.3 ms of CPU
// a frame on an H200).

#include "GlObjects.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

class GpuReadback {
public:
    // Room for `values` 32-bit values; the latest read starts as zeros.
    explicit GpuReadback(size_t values = 1) : latest_(values, 0) {}

    // The buffer the next read's values go to, for a shader to write them into (bound as a storage
    // buffer): from here to the next mark() a read is pending.
    GLuint target();
    // Marks the writes queued into target() since the last mark as one read (after a
    // GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT barrier), and sends the next read to the next buffer of the
    // ring; nothing when no read is pending.
    void mark();
    // Drops the reads not taken yet (and a pending one), and their values: the latest read becomes
    // zeros, and none has been read.
    void reset();
    // The values of the latest read the GPU has finished (the latest marked when `wait`).
    const std::vector<uint32_t>& latest(bool wait);
    // The values latest() last gave, without a new look at the marks.
    const std::vector<uint32_t>& values() const { return latest_; }
    // Whether a read has finished since construction or reset(): the values are the GPU's.
    bool hasRead() const { return hasRead_; }

private:
    static constexpr size_t kRing = 3;
    struct Slot {
        GlBuffer buffer;
        const uint32_t* mapped = nullptr; // the buffer, mapped persistently for reading
        GlQuery query;
        uint64_t marked = 0; // the mark's number (from 1); 0: none to read
    };
    Slot& current(); // made on first use
    void read(Slot& slot);

    std::array<Slot, kRing> slots_;
    size_t current_ = 0;   // the slot target() gives
    bool pending_ = false; // target() given since the last mark
    uint64_t marks_ = 0;   // marks made
    uint64_t readTo_ = 0;  // the newest mark read or dropped
    std::vector<uint32_t> latest_;
    bool hasRead_ = false;
};

} // namespace spatter::render_detail
