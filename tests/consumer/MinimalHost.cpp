// A minimal host of spatter's decal projector, built against the installed headers only: a 64x64
// G-buffer whose depth holds a wall at z = 0 seen from z = 2, one decal on it, one draw. It exits 0
// when the decal changed the wall's albedo under it and left the corners alone, 1 on any error, and
// 77 (skipped) when no headless OpenGL 4.5 context can be made.

#include <spatter/render/DecalProjector.hpp>
#include <spatter/render/GlContext.hpp>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <vector>

namespace {

constexpr int kSize = 64;

GLuint texture(GLenum format) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, kSize, kSize);
    return t;
}

} // namespace

int main() {
    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) {
        std::fprintf(stderr, "no headless OpenGL 4.5 context: %s\n", gl.error().c_str());
        return 77;
    }

    // The host's frame: a wall at z = 0 filling the view, standard Z, GL's default clip depth.
    const glm::dmat4 view = glm::lookAt(glm::dvec3(0, 0, 2), glm::dvec3(0, 0, 0), glm::dvec3(0, 1, 0));
    const glm::dmat4 projection = glm::perspective(glm::radians(60.0), 1.0, 0.1, 100.0);
    const glm::dvec4 clip = projection * view * glm::dvec4(0, 0, 0, 1);
    const float wallDepth = float(clip.z / clip.w * 0.5 + 0.5);
    const GLuint depth = texture(GL_DEPTH_COMPONENT32F), normals = texture(GL_RGBA8),
                 albedo = texture(GL_RGBA8);
    glClearTexImage(depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &wallDepth);
    const unsigned char up[4] = {128, 128, 255, 255}, grey[4] = {128, 128, 128, 255};
    glClearTexImage(normals, 0, GL_RGBA, GL_UNSIGNED_BYTE, up);
    glClearTexImage(albedo, 0, GL_RGBA, GL_UNSIGNED_BYTE, grey);

    spatter::Result<spatter::DecalProjector> projector = spatter::DecalProjector::create();
    if (!projector) {
        std::fprintf(stderr, "%s\n", projector.error().c_str());
        return 1;
    }
    spatter::DecalType paint;
    paint.name = "paint";
    paint.texture = int(spatter::DecalTexture::Paint);
    projector->setDecalTypes({paint});
    spatter::Decal decal;
    decal.setFrame({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}); // tangent, bitangent, normal: facing +z
    decal.size = glm::vec2(1.0f);
    decal.halfDepth = 0.1f;
    if (!projector->setObjects({glm::dmat4(1.0)}, {0})) return 1;
    projector->setDecals({decal});

    spatter::HostFrame frame;
    frame.width = frame.height = kSize;
    frame.view = view;
    frame.projection = projection;
    frame.eye = glm::dvec3(0, 0, 2);
    frame.depth = {depth, spatter::DepthEncoding::Window, spatter::ClipDepth::MinusOneToOne, false};
    frame.normals = {normals, spatter::NormalEncoding::WorldUnorm};
    frame.albedoTexture = albedo;
    spatter::Result<spatter::ProjectorStats> stats = projector->draw(frame);
    if (!stats) {
        std::fprintf(stderr, "%s\n", stats.error().c_str());
        return 1;
    }

    std::vector<unsigned char> pixels(size_t(kSize) * kSize * 4);
    glGetTextureImage(albedo, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    size_t changed = 0;
    for (size_t i = 0; i < pixels.size(); i += 4)
        changed += pixels[i] != grey[0] || pixels[i + 1] != grey[1] || pixels[i + 2] != grey[2] ? 1 : 0;
    const bool cornerKept = pixels[0] == grey[0] && pixels[1] == grey[1] && pixels[2] == grey[2];
    std::printf("spatter-consumer: %zu decal drawn, %zu pixels changed (%s)\n", stats->drawn, changed,
                stats->variant.c_str());
    return stats->drawn == 1 && changed > 50 && cornerKept ? 0 : 1;
}
