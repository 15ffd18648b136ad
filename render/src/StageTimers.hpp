#pragma once
// StageTimers: GPU timestamps at the boundaries of the projector's pass (ProjectorSettings::
// stageTimers), so that its time splits into culling, binning, drawing and read-back
// (ProjectorStageTimes). One set of GL_TIMESTAMP queries per frame in a ring of frames, read without
// stalling as GpuTimers reads its own: the newest frame whose queries have all finished, or with
// `wait` the current one.

#include "GlObjects.hpp"

#include "spatter/render/DecalProjector.hpp"

#include <array>
#include <cstdint>

namespace spatter::render_detail {

// The ends of the pass's stages, in the order they come.
enum class PassStage { Start = 0, Culled, Binned, Drawn, ReadBack, Count };

class StageTimers {
public:
    void create();
    // Starts frame `frame`'s set and marks its start.
    void beginFrame(uint64_t frame);
    // Marks the end of `stage`; a stage before it not marked yet ends where the one before it ended
    // (it took no time). A stage marked already keeps its mark.
    void mark(PassStage stage);
    // Marks the stages not marked yet and returns the newest finished frame's times.
    ProjectorStageTimes endFrame(bool wait);

private:
    static constexpr int kRing = 4;
    static constexpr int kMarks = int(PassStage::Count);
    struct Slot {
        std::array<GlQuery, kMarks> queries;
        std::array<int, kMarks> source{}; // the query holding each mark's time (its own, or a skipped
                                          // stage's: the mark before it)
        int marked = 0;                   // marks made this frame
        int64_t frame = -1;               // frame whose queries are in flight, -1 when read or unused
    };
    bool available(const Slot& slot) const;
    void read(Slot& slot);

    std::array<Slot, kRing> slots_;
    int current_ = 0;
    ProjectorStageTimes latest_;
};

} // namespace spatter::render_detail
