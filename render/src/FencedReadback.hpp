#pragma once
// FencedReadback: a few 32-bit values the GPU writes into buffers, copied into a buffer of its own
// (or written there by a shader) after the commands that write them and read on the CPU once the GPU has
// passed a fence, without a stall unless asked: GpuCulling's counts, ForwardBins' decals-left-out flag.

#include "GlObjects.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

class FencedReadback {
public:
    // Room for `values` 32-bit values; the latest read starts as zeros.
    explicit FencedReadback(size_t values = 1) : latest_(values, 0) {}
    FencedReadback(const FencedReadback&) = delete;
    FencedReadback& operator=(const FencedReadback&) = delete;
    ~FencedReadback();

    // Copies `count` values from `buffer` at byte `offset` to value `first` (after the commands queued
    // so far).
    void copy(GLuint buffer, size_t offset, size_t first, size_t count);
    // The buffer the values are read from, for a shader to write them into (bound as a storage
    // buffer) in place of copy().
    GLuint target();
    // Marks the copies queued since the last fence as one read.
    void fence();
    // Drops a read not taken yet, and its values: the latest read becomes zeros, and none has been read.
    void reset();
    // The values of the latest read the GPU has finished (this one's when `wait`).
    const std::vector<uint32_t>& latest(bool wait);
    // The values latest() last gave, without a new look at the fence.
    const std::vector<uint32_t>& values() const { return latest_; }
    // Whether a read has finished since construction or reset(): the values are the GPU's.
    bool hasRead() const { return hasRead_; }

private:
    GlBuffer buffer_;
    GLsync fence_ = nullptr;
    std::vector<uint32_t> latest_;
    bool hasRead_ = false;
};

} // namespace spatter::render_detail
