#include "DepthPyramid.hpp"

#include "PowerOfTwo.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>

namespace spatter::render_detail {

namespace {

int convention(const HostFrame& f) {
    if (f.depth.encoding == DepthEncoding::LinearView) return 2;
    return f.depth.reversedZ ? 1 : 0;
}

GLuint groups(int size) {
    return GLuint((size + 7) / 8);
}

} // namespace

void DepthPyramid::allocate(glm::ivec2 size) {
    if (texture_ && size == size_) return;
    size_ = size;
    levels_ = 1;
    for (int s = std::max(size.x, size.y); s > 1; s /= 2)
        ++levels_;
    texture_ = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.get(), levels_, GL_R32F, size.x, size.y);
    // texelFetch reaches the levels above the base only with a mipmap filter.
    glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

Status DepthPyramid::prepare(const HostFrame& f) {
    const int c = convention(f);
    if (programs_[c]) return {};
    const char* defines[3] = {"STANDARD_Z", "REVERSED_Z", "DEPTH_LINEAR"};
    Result<GlProgram> p = projectorComputeProgram("depth_pyramid.comp", {defines[c]});
    if (!p) return fail(p.error());
    programs_[c] = std::move(p.value());
    return {};
}

Occlusion DepthPyramid::build(const HostFrame& f, GLuint sampler) {
    const int c = convention(f);
    allocate({int(nextPowerOfTwo(uint64_t((f.width + 1) / 2))),
              int(nextPowerOfTwo(uint64_t((f.height + 1) / 2)))});
    glUseProgram(programs_[c].get());
    glBindTextureUnit(0, f.depth.texture);
    glBindSampler(0, sampler);
    glUniform4i(0, f.x, f.y, f.width, f.height);
    for (int level = 0; level < levels_; ++level) {
        glBindImageTexture(0, texture_.get(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        if (level > 0) glBindImageTexture(1, texture_.get(), level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
        glUniform1i(1, level);
        const int w = std::max(1, size_.x >> level), h = std::max(1, size_.y >> level);
        glDispatchCompute(groups(w), groups(h), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    return Occlusion{texture_.get(), levels_, c, size_};
}

size_t DepthPyramid::gpuBytes() const {
    size_t bytes = 0;
    for (int level = 0; level < levels_; ++level)
        bytes += size_t(std::max(1, size_.x >> level)) * size_t(std::max(1, size_.y >> level)) * 4;
    return bytes;
}

} // namespace spatter::render_detail
