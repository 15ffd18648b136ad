#include "GpuReadback.hpp"

#include <algorithm>

namespace spatter::render_detail {

GpuReadback::Slot& GpuReadback::current() {
    Slot& slot = slots_[current_];
    if (!slot.buffer) {
        const auto bytes = GLsizeiptr(latest_.size() * sizeof(uint32_t));
        const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        slot.buffer = createBuffer();
        glNamedBufferStorage(slot.buffer.get(), bytes, nullptr, access | GL_CLIENT_STORAGE_BIT);
        slot.mapped =
            static_cast<const uint32_t*>(glMapNamedBufferRange(slot.buffer.get(), 0, bytes, access));
        GLuint q = 0;
        glCreateQueries(GL_TIMESTAMP, 1, &q);
        slot.query = GlQuery(q);
    }
    return slot;
}

GLuint GpuReadback::target() {
    pending_ = true;
    return current().buffer.get();
}

void GpuReadback::mark() {
    if (!pending_) return;
    pending_ = false;
    glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    Slot& slot = current();
    glQueryCounter(slot.query.get(), GL_TIMESTAMP);
    slot.marked = ++marks_;
    current_ = (current_ + 1) % kRing;
    slots_[current_].marked = 0; // a read of three marks ago not taken by now is dropped
}

void GpuReadback::reset() {
    for (Slot& s : slots_)
        s.marked = 0;
    pending_ = false;
    readTo_ = marks_;
    std::fill(latest_.begin(), latest_.end(), 0u);
    hasRead_ = false;
}

void GpuReadback::read(Slot& slot) {
    GLuint64 passed = 0; // waits for the mark where it has not been passed
    glGetQueryObjectui64v(slot.query.get(), GL_QUERY_RESULT, &passed);
    if (slot.mapped) std::copy(slot.mapped, slot.mapped + latest_.size(), latest_.begin());
    readTo_ = slot.marked;
    slot.marked = 0;
    hasRead_ = true;
}

const std::vector<uint32_t>& GpuReadback::latest(bool wait) {
    // The newest mark first: an older one is not worth reading once a newer one has been passed.
    for (size_t k = 1; k <= kRing; ++k) {
        Slot& slot = slots_[(current_ + kRing - k) % kRing];
        if (slot.marked == 0 || slot.marked <= readTo_) continue;
        GLint available = GL_FALSE;
        if (!wait) glGetQueryObjectiv(slot.query.get(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (wait || available == GL_TRUE) {
            read(slot);
            break;
        }
    }
    return latest_;
}

} // namespace spatter::render_detail
