#include "StageTimers.hpp"

namespace spatter::render_detail {

void StageTimers::create() {
    for (Slot& s : slots_)
        for (GlQuery& q : s.queries) {
            GLuint n = 0;
            glCreateQueries(GL_TIMESTAMP, 1, &n);
            q = GlQuery(n);
        }
}

void StageTimers::beginFrame(uint64_t frame) {
    current_ = int(frame % kRing);
    Slot& slot = slots_[size_t(current_)];
    // The slot's previous frame is kRing frames old; its results are certainly there by now.
    if (slot.frame >= 0) read(slot);
    slot.marked = 0;
    slot.frame = int64_t(frame);
    mark(PassStage::Start);
}

void StageTimers::mark(PassStage stage) {
    Slot& slot = slots_[size_t(current_)];
    const int s = int(stage);
    if (s < slot.marked) return;
    for (int k = slot.marked; k < s; ++k)
        slot.source[size_t(k)] = slot.source[size_t(k - 1)];
    glQueryCounter(slot.queries[size_t(s)].get(), GL_TIMESTAMP);
    slot.source[size_t(s)] = s;
    slot.marked = s + 1;
}

bool StageTimers::available(const Slot& slot) const {
    GLint done = GL_FALSE;
    glGetQueryObjectiv(slot.queries[kMarks - 1].get(), GL_QUERY_RESULT_AVAILABLE, &done);
    return done == GL_TRUE; // the last mark finishes after the others
}

void StageTimers::read(Slot& slot) {
    std::array<GLuint64, kMarks> ns{};
    for (size_t k = 0; k < kMarks; ++k) {
        if (slot.source[k] == int(k))
            glGetQueryObjectui64v(slot.queries[k].get(), GL_QUERY_RESULT, &ns[k]);
        else
            ns[k] = ns[size_t(slot.source[k])];
    }
    auto ms = [&](PassStage end) {
        const size_t e = size_t(end);
        return ns[e] > ns[e - 1] ? double(ns[e] - ns[e - 1]) * 1e-6 : 0.0;
    };
    if (slot.frame > latest_.frame) {
        latest_.frame = slot.frame;
        latest_.cullMs = ms(PassStage::Culled);
        latest_.binMs = ms(PassStage::Binned);
        latest_.drawMs = ms(PassStage::Drawn);
        latest_.readBackMs = ms(PassStage::ReadBack);
    }
    slot.frame = -1;
}

ProjectorStageTimes StageTimers::endFrame(bool wait) {
    mark(PassStage::ReadBack);
    if (wait) {
        read(slots_[size_t(current_)]);
        return latest_;
    }
    // Oldest first, so that `latest_` ends at the newest finished frame.
    for (int k = 1; k <= kRing; ++k) {
        Slot& slot = slots_[size_t((current_ + k) % kRing)];
        if (slot.frame >= 0 && available(slot)) read(slot);
    }
    return latest_;
}

} // namespace spatter::render_detail
