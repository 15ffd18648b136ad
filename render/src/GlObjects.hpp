#pragma once
// Move-only owners of OpenGL object names. Each deletes its name when destroyed, so the context
// must be current then.

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>
#include <utility>

namespace spatter::render_detail {

enum class GlKind { Buffer, Texture, Framebuffer, VertexArray, Query, Program, Shader, Sampler };

inline void deleteGlName(GlKind kind, GLuint name) {
    switch (kind) {
    case GlKind::Buffer:
        glDeleteBuffers(1, &name);
        break;
    case GlKind::Texture:
        glDeleteTextures(1, &name);
        break;
    case GlKind::Framebuffer:
        glDeleteFramebuffers(1, &name);
        break;
    case GlKind::VertexArray:
        glDeleteVertexArrays(1, &name);
        break;
    case GlKind::Query:
        glDeleteQueries(1, &name);
        break;
    case GlKind::Program:
        glDeleteProgram(name);
        break;
    case GlKind::Shader:
        glDeleteShader(name);
        break;
    case GlKind::Sampler:
        glDeleteSamplers(1, &name);
        break;
    }
}

template <GlKind Kind> class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;
    GlName(GlName&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    GlName& operator=(GlName&& o) noexcept {
        if (this != &o) {
            reset();
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }
    ~GlName() { reset(); }

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_) deleteGlName(Kind, name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

using GlBuffer = GlName<GlKind::Buffer>;
using GlTexture = GlName<GlKind::Texture>;
using GlFramebuffer = GlName<GlKind::Framebuffer>;
using GlVertexArray = GlName<GlKind::VertexArray>;
using GlQuery = GlName<GlKind::Query>;
using GlProgram = GlName<GlKind::Program>;
using GlShader = GlName<GlKind::Shader>;
using GlSampler = GlName<GlKind::Sampler>;

inline GlBuffer createBuffer() {
    GLuint n = 0;
    glCreateBuffers(1, &n);
    return GlBuffer(n);
}

// A new buffer of `capacity` bytes (immutable storage, GL_DYNAMIC_STORAGE_BIT, contents undefined).
inline GlBuffer dynamicBuffer(size_t capacity) {
    GlBuffer buffer = createBuffer();
    glNamedBufferStorage(buffer.get(), GLsizeiptr(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
    return buffer;
}

// Grows `buffer` (dynamicBuffer) to hold `bytes`, doubling from at least `minimum`; true when it was
// recreated (its contents are then undefined).
inline bool reserveBuffer(GlBuffer& buffer, size_t& capacity, size_t bytes, size_t minimum) {
    if (bytes <= capacity && buffer) return false;
    capacity = capacity > minimum ? capacity : minimum;
    while (capacity < bytes)
        capacity *= 2;
    buffer = dynamicBuffer(capacity);
    return true;
}

// Grows `buffer` like reserveBuffer, keeping the first `keep` bytes of the old buffer (copied on the
// GPU), but by a quarter of its capacity (at least `minimum`), or to `bytes` itself where that is
// more: a large batch takes no room to spare, a stream of small ones a copy now and then.
inline bool growBuffer(GlBuffer& buffer, size_t& capacity, size_t bytes, size_t minimum, size_t keep) {
    if (bytes <= capacity && buffer) return false;
    GlBuffer old = std::move(buffer);
    const size_t oldCapacity = old ? capacity : 0;
    capacity = std::max({bytes, oldCapacity + oldCapacity / 4, minimum});
    buffer = dynamicBuffer(capacity);
    keep = keep < oldCapacity ? keep : oldCapacity;
    if (keep > 0) glCopyNamedBufferSubData(old.get(), buffer.get(), 0, 0, GLsizeiptr(keep));
    return true;
}

inline GlTexture createTexture(GLenum target) {
    GLuint n = 0;
    glCreateTextures(target, 1, &n);
    return GlTexture(n);
}

inline GlFramebuffer createFramebuffer() {
    GLuint n = 0;
    glCreateFramebuffers(1, &n);
    return GlFramebuffer(n);
}

inline GlSampler createSampler() {
    GLuint n = 0;
    glCreateSamplers(1, &n);
    return GlSampler(n);
}

inline GlVertexArray createVertexArray() {
    GLuint n = 0;
    glCreateVertexArrays(1, &n);
    return GlVertexArray(n);
}

} // namespace spatter::render_detail
