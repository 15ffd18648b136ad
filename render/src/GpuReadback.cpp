#include "GpuReadback.hpp"

#include <algorithm>

namespace spatter::render_detail {

GLuint GpuReadback::target() {
    if (!buffer_) {
        buffer_ = createBuffer();
        glNamedBufferStorage(buffer_.get(), GLsizeiptr(latest_.size() * sizeof(uint32_t)), nullptr,
                             GL_CLIENT_STORAGE_BIT);
        GLuint q = 0;
        glCreateQueries(GL_TIMESTAMP, 1, &q);
        query_ = GlQuery(q);
    }
    return buffer_.get();
}

void GpuReadback::mark() {
    target();
    glQueryCounter(query_.get(), GL_TIMESTAMP);
    pending_ = true;
}

void GpuReadback::reset() {
    pending_ = false;
    std::fill(latest_.begin(), latest_.end(), 0u);
    hasRead_ = false;
}

const std::vector<uint32_t>& GpuReadback::latest(bool wait) {
    if (!pending_) return latest_;
    if (!wait) {
        GLint available = GL_FALSE;
        glGetQueryObjectiv(query_.get(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available != GL_TRUE) return latest_;
    }
    GLuint64 passed = 0; // waits for the mark when `wait`
    glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &passed);
    glGetNamedBufferSubData(buffer_.get(), 0, GLsizeiptr(latest_.size() * sizeof(uint32_t)), latest_.data());
    pending_ = false;
    hasRead_ = true;
    return latest_;
}

} // namespace spatter::render_detail
