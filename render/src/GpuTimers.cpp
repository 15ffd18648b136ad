#include "GpuTimers.hpp"

namespace spatter::render_detail {

void GpuTimers::create() {
    for (Slot& s : slots_)
        for (GlQuery& q : s.queries) {
            GLuint n = 0;
            glCreateQueries(GL_TIME_ELAPSED, 1, &n);
            q = GlQuery(n);
        }
    GLuint warm = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &warm);
    warmQuery_ = GlQuery(warm);
    warmTarget_ = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(warmTarget_.get(), 1, GL_RGBA8, 1, 1);
    warmFbo_ = createFramebuffer();
    glNamedFramebufferTexture(warmFbo_.get(), GL_COLOR_ATTACHMENT0, warmTarget_.get(), 0);
    warmUp();
    GLuint64 discard = 0;
    glGetQueryObjectui64v(warmQuery_.get(), GL_QUERY_RESULT, &discard);
}

// llvmpipe measures the first timed interval of a context, and the first after a compute dispatch
// outside any timed interval (untimedWork), from an arbitrary origin (hours); a timed clear of a
// scratch target takes that interval: once here, and ahead of the next frame's passes after such work.
void GpuTimers::warmUp() {
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glBeginQuery(GL_TIME_ELAPSED, warmQuery_.get());
    glClearNamedFramebufferfv(warmFbo_.get(), GL_COLOR, 0, zero);
    glEndQuery(GL_TIME_ELAPSED);
}

void GpuTimers::read(Slot& slot) {
    double ms[kPasses] = {};
    for (int p = 0; p < kPasses; ++p) {
        if (!slot.used[size_t(p)]) continue;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(slot.queries[size_t(p)].get(), GL_QUERY_RESULT, &ns);
        ms[p] = double(ns) * 1e-6;
    }
    if (slot.frame > latest_.frame) {
        latest_.frame = slot.frame;
        latest_.geometryMs = ms[int(GpuPass::Geometry)];
        latest_.decalsMs = ms[int(GpuPass::Decals)];
        latest_.lateMs = ms[int(GpuPass::Late)];
        latest_.lightingMs = ms[int(GpuPass::Lighting)];
        latest_.overlayMs = ms[int(GpuPass::Overlay)];
        latest_.splatMs = ms[int(GpuPass::Splat)];
        latest_.volumetricMs = ms[int(GpuPass::Volumetric)];
    }
    slot.frame = -1;
}

void GpuTimers::beginFrame(uint64_t frame) {
    current_ = int(frame % kRing);
    Slot& slot = slots_[size_t(current_)];
    // The slot's previous frame is kRing frames old; its results are certainly there by now.
    if (slot.frame >= 0) read(slot);
    slot.used.fill(false);
    slot.frame = int64_t(frame);
    if (untimedWork_) warmUp();
    untimedWork_ = false;
}

void GpuTimers::begin(GpuPass pass) {
    Slot& slot = slots_[size_t(current_)];
    glBeginQuery(GL_TIME_ELAPSED, slot.queries[size_t(pass)].get());
    slot.used[size_t(pass)] = true;
    active_ = true;
}

void GpuTimers::end() {
    if (!active_) return;
    glEndQuery(GL_TIME_ELAPSED);
    active_ = false;
}

GpuPassTimes GpuTimers::endFrame(bool wait) {
    end();
    if (wait) {
        read(slots_[size_t(current_)]);
        return latest_;
    }
    // Oldest first, so that `latest_` ends at the newest complete frame.
    for (int k = 1; k <= kRing; ++k) {
        Slot& slot = slots_[size_t((current_ + k) % kRing)];
        if (slot.frame < 0) continue;
        bool ready = true;
        for (int p = 0; p < kPasses && ready; ++p) {
            if (!slot.used[size_t(p)]) continue;
            GLint available = GL_FALSE;
            glGetQueryObjectiv(slot.queries[size_t(p)].get(), GL_QUERY_RESULT_AVAILABLE, &available);
            ready = available == GL_TRUE;
        }
        if (ready) read(slot);
    }
    return latest_;
}

} // namespace spatter::render_detail
