#include "FencedReadback.hpp"

#include <algorithm>

namespace spatter::render_detail {

FencedReadback::~FencedReadback() {
    if (fence_) glDeleteSync(fence_);
}

void FencedReadback::copy(GLuint buffer, size_t offset, size_t first, size_t count) {
    glCopyNamedBufferSubData(buffer, target(), GLintptr(offset), GLintptr(first * sizeof(uint32_t)),
                             GLsizeiptr(count * sizeof(uint32_t)));
}

GLuint FencedReadback::target() {
    if (!buffer_) {
        buffer_ = createBuffer();
        glNamedBufferStorage(buffer_.get(), GLsizeiptr(latest_.size() * sizeof(uint32_t)), nullptr,
                             GL_CLIENT_STORAGE_BIT);
    }
    return buffer_.get();
}

void FencedReadback::fence() {
    if (fence_) glDeleteSync(fence_);
    fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

void FencedReadback::reset() {
    if (fence_) glDeleteSync(fence_);
    fence_ = nullptr;
    std::fill(latest_.begin(), latest_.end(), 0u);
    hasRead_ = false;
}

const std::vector<uint32_t>& FencedReadback::latest(bool wait) {
    if (!fence_) return latest_;
    const GLenum state =
        glClientWaitSync(fence_, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, wait ? ~GLuint64(0) : 0);
    if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) return latest_;
    glGetNamedBufferSubData(buffer_.get(), 0, GLsizeiptr(latest_.size() * sizeof(uint32_t)), latest_.data());
    glDeleteSync(fence_);
    fence_ = nullptr;
    hasRead_ = true;
    return latest_;
}

} // namespace spatter::render_detail
