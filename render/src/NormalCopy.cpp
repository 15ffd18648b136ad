#include "NormalCopy.hpp"

#include "HostFrameCheck.hpp"
#include "ProjectorShaders.hpp"
#include "ShaderProgram.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::render_detail {

namespace {

// Whole pixels around a box's screen rectangle (normalised device bounds), a pixel wider for the
// derivatives of the decal pass, clamped to the viewport: x0, y0, x1, y1 (end exclusive).
glm::ivec4 pixelRect(const glm::vec4& r, int width, int height) {
    return glm::ivec4(std::max(0, int(std::floor((r.x * 0.5f + 0.5f) * float(width))) - 1),
                      std::max(0, int(std::floor((r.y * 0.5f + 0.5f) * float(height))) - 1),
                      std::min(width, int(std::ceil((r.z * 0.5f + 0.5f) * float(width))) + 1),
                      std::min(height, int(std::ceil((r.w * 0.5f + 0.5f) * float(height))) + 1));
}

bool disjoint(const DecalVisibility& vis, int width, int height) {
    std::vector<glm::ivec4> px;
    for (const glm::vec4& r : vis.rects)
        px.push_back(pixelRect(r, width, height));
    for (size_t a = 0; a < px.size(); ++a)
        for (size_t b = a + 1; b < px.size(); ++b)
            if (px[a].x < px[b].z && px[b].x < px[a].z && px[a].y < px[b].w && px[b].y < px[a].w)
                return false;
    return true;
}

} // namespace

NormalCopyMode normalCopyMode(const DecalVisibility& vis, int width, int height, bool inPlace) {
    if (inPlace && vis.rects.size() <= kInPlaceDecals && disjoint(vis, width, height))
        return NormalCopyMode::InPlace;
    double area = 0.0; // in units of the viewport (NDC spans 2 x 2); a box that may hold the eye: 1
    for (const glm::vec4& r : vis.rects)
        area += double(r.z - r.x) * double(r.w - r.y) / 4.0;
    if (area > 0.25) return NormalCopyMode::Viewport;
    return vis.rects.size() <= kRectCopyDecals ? NormalCopyMode::Rects : NormalCopyMode::Boxes;
}

NormalCopyMode normalCopyMode(uint32_t gpuVisible) {
    return gpuVisible <= kBoxCopyDecals ? NormalCopyMode::Boxes : NormalCopyMode::Viewport;
}

const char* normalCopyName(NormalCopyMode mode) {
    switch (mode) {
    case NormalCopyMode::InPlace:
        return "in-place";
    case NormalCopyMode::Rects:
        return "rects";
    case NormalCopyMode::Boxes:
        return "boxes";
    case NormalCopyMode::Viewport:
        return "viewport";
    case NormalCopyMode::None:
        break;
    }
    return "";
}

Status NormalCopy::prepare() {
    if (program_) return {};
    Result<GlProgram> p =
        buildProgram(shaderLibrary(kProjectorShaders),
                     {{GL_VERTEX_SHADER, "decal.vert"}, {GL_FRAGMENT_SHADER, "normal_copy.frag"}}, {});
    if (!p) return fail("projector: " + p.error());
    program_ = std::move(p.value());
    return {};
}

void NormalCopy::allocate(GLuint hostNormals) {
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(hostNormals, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(hostNormals, 0, GL_TEXTURE_HEIGHT, &h);
    const GLenum format = textureFormat(hostNormals);
    if (texture_ && format == format_ && w == width_ && h == height_) return;
    texture_ = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.get(), 1, format, w, h);
    // Defined from the start: a box copy leaves the rest as it was, and the decal pass's derivatives
    // read a neighbour or two beyond the boxes.
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(texture_.get(), 0, GL_RGBA, GL_FLOAT, zero);
    format_ = format;
    width_ = w;
    height_ = h;
    GLint bits = 0;
    for (GLenum channel :
         {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE}) {
        GLint b = 0;
        glGetTextureLevelParameteriv(texture_.get(), 0, channel, &b);
        bits += b;
    }
    bytes_ = size_t(w) * size_t(h) * size_t(bits) / 8;
}

void NormalCopy::release() {
    texture_.reset(); // allocate() makes a texture anew when there is none
    bytes_ = 0;
}

void NormalCopy::copyViewport(const HostFrame& f) const {
    glCopyImageSubData(f.normals.texture, GL_TEXTURE_2D, 0, f.x, f.y, 0, texture_.get(), GL_TEXTURE_2D, 0,
                       f.x, f.y, 0, f.width, f.height, 1);
}

void NormalCopy::copyRects(const HostFrame& f, const DecalVisibility& vis) const {
    for (const glm::vec4& r : vis.rects) {
        const glm::ivec4 p = pixelRect(r, f.width, f.height);
        const int x0 = p.x, y0 = p.y, x1 = p.z, y1 = p.w;
        if (x1 <= x0 || y1 <= y0) continue;
        glCopyImageSubData(f.normals.texture, GL_TEXTURE_2D, 0, f.x + x0, f.y + y0, 0, texture_.get(),
                           GL_TEXTURE_2D, 0, f.x + x0, f.y + y0, 0, x1 - x0, y1 - y0, 1);
    }
}

} // namespace spatter::render_detail
