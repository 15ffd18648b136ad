#pragma once
// GPU timer queries (GL_TIME_ELAPSED), one per pass and frame, in a ring of frames. Results are
// read without stalling: at the end of each frame the newest frame whose queries have all
// finished is read. wait = true reads the current frame's results at once (tools, benchmarks).

#include "GlObjects.hpp"

#include "spatter/render/FrameStats.hpp"

#include <array>
#include <cstdint>

namespace spatter::render_detail {

enum class GpuPass { Geometry = 0, Decals, Late, Lighting, Overlay, Splat, Volumetric, Count };

class GpuTimers {
public:
    void create();
    void beginFrame(uint64_t frame);
    void begin(GpuPass pass);
    void end();
    // Ends the frame and returns the newest complete results (frame -1 while there are none).
    GpuPassTimes endFrame(bool wait);
    // Says that GPU work ran outside the frame's timed passes (a compute dispatch between frames).
    void untimedWork() { untimedWork_ = true; }

private:
    static constexpr int kRing = 4;
    static constexpr int kPasses = int(GpuPass::Count);
    struct Slot {
        std::array<GlQuery, kPasses> queries;
        std::array<bool, kPasses> used{};
        int64_t frame = -1; // frame whose queries are in flight, -1 when read or unused
    };
    void read(Slot& slot);
    // A timed clear of a 1 x 1 scratch target, whose time is not read (see create and beginFrame).
    void warmUp();

    std::array<Slot, kRing> slots_;
    GlQuery warmQuery_;
    GlTexture warmTarget_;
    GlFramebuffer warmFbo_;
    bool untimedWork_ = false;
    int current_ = 0;
    bool active_ = false;
    GpuPassTimes latest_;
};

} // namespace spatter::render_detail
