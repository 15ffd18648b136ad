#include "DepthPyramid.hpp"

#include "ProjectorVariants.hpp"

#include <algorithm>
#include <utility>

namespace spatter::render_detail {

namespace {

int convention(const HostFrame& f) {
    if (f.depth.encoding == DepthEncoding::LinearView) return 2;
    return f.depth.reversedZ ? 1 : 0;
}

GLuint groups(int size) {
    return GLuint((size + 7) / 8);
}

// The most levels: a box wider than the top level's texels reads several of them.
constexpr int kMaxLevels = 7;
// A level-0 texel's pixels a side (kTexelPixels in depth_pyramid.comp, kPyramidTexelPixels in
// cull_exact.comp).
constexpr int kTexelPixels = 4;

// Level 0 for a viewport of `width` x `height`: a texel per kTexelPixels a side, rounded up to a
// multiple of the top level's footprint, so that every level halves the one below exactly (GL's mip
// levels round down, which would drop an odd level's last row), and the number of levels.
std::pair<glm::ivec2, int> levelZero(int width, int height) {
    const glm::ivec2 texels((width + kTexelPixels - 1) / kTexelPixels,
                            (height + kTexelPixels - 1) / kTexelPixels);
    int levels = 1;
    while (levels < kMaxLevels && (1 << levels) <= std::max(texels.x, texels.y))
        ++levels;
    const int step = 1 << (levels - 1);
    return {(texels + step - 1) / step * step, levels};
}

} // namespace

void DepthPyramid::allocate(glm::ivec2 size, int levels) {
    if (texture_ && size == size_ && levels == levels_) return;
    size_ = size;
    levels_ = levels;
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
    const auto [size, levels] = levelZero(f.width, f.height);
    allocate(size, levels);
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
