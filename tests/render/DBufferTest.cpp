// The projector's DBuffer path: decals drawn into the projector's own decal buffers, the host's
// G-buffer only read, and the buffers applied by a host shader through hostShader("dbuffer.glsl")
// give what the G-buffer blend gives.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/render/DecalProjector.hpp"

#include <epoxy/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

// A host's full-screen pass applying the decal buffers to its G-buffer (albedo RGBA8, world normals
// as n * 0.5 + 0.5, roughness in G), written to three new textures of the same layout.
const char* kApplyVert = R"(
void main() {
    vec2 p = vec2((gl_VertexID & 1) != 0 ? 3.0 : -1.0, (gl_VertexID & 2) != 0 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

const char* kApplyFrag = R"(
layout(binding = 0) uniform sampler2D s_albedo;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform sampler2D s_material;
layout(binding = 3) uniform sampler2D s_dbufferAlbedo;
layout(binding = 4) uniform sampler2D s_dbufferNormal;
layout(binding = 5) uniform sampler2D s_dbufferMaterial;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 albedo = texelFetch(s_albedo, p, 0);
    vec3 n = normalize(texelFetch(s_normal, p, 0).xyz * 2.0 - 1.0);
    vec4 material = texelFetch(s_material, p, 0);
    o_albedo = vec4(spatterDBufferAlbedo(s_dbufferAlbedo, p, albedo.rgb), albedo.a);
    o_normal = vec4(spatterDBufferNormal(s_dbufferNormal, p, n) * 0.5 + 0.5, 1.0);
    o_material = vec4(material.r, spatterDBufferRoughness(s_dbufferMaterial, p, material.g), 0.0, 0.0);
}
)";

GLuint compileStage(GLenum stage, const std::string& text) {
    const GLuint s = glCreateShader(stage);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    EXPECT_EQ(ok, GL_TRUE);
    return s;
}

GLuint newTexture(GLenum format) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, kWallWidth, kWallHeight);
    return t;
}

// The host's G-buffer of `f` with the decal buffers applied: albedo, normal and material textures.
struct Applied {
    GLuint albedo = newTexture(GL_RGBA8), normal = newTexture(GL_RGB10_A2), material = newTexture(GL_RG8);
    ~Applied() {
        const GLuint t[3] = {albedo, normal, material};
        glDeleteTextures(3, t);
    }
};

void applyDBuffer(const HostFrame& f, const ProjectorResources& r, const Applied& out) {
    Result<std::string> include = DecalProjector::hostShader("dbuffer.glsl");
    ASSERT_TRUE(include.ok()) << include.error();
    const std::string head = "#version 450 core\n" + include.value();
    const GLuint vs = compileStage(GL_VERTEX_SHADER, "#version 450 core\n" + std::string(kApplyVert));
    const GLuint fs = compileStage(GL_FRAGMENT_SHADER, head + kApplyFrag);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    GLuint fbo = 0, vao = 0;
    glCreateFramebuffers(1, &fbo);
    glCreateVertexArrays(1, &vao);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, out.albedo, 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, out.normal, 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, out.material, 0);
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(fbo, 3, buffers);
    const GLuint inputs[6] = {f.albedoTexture, f.normals.texture, f.roughness.texture,
                              r.dbufferAlbedo, r.dbufferNormal,   r.dbufferMaterial};
    glBindTextures(0, 6, inputs);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, kWallWidth, kWallHeight);
    glUseProgram(program);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTextures(0, 6, nullptr);
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
}

// The largest difference of channels [first, last) over all pixels, in 1/255.
int largestDifference(const Image& a, const Image& b, int first, int last) {
    int worst = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        for (int c = first; c < last; ++c)
            worst = std::max(worst, std::abs(int(a.rgba[i + size_t(c)]) - int(b.rgba[i + size_t(c)])));
    return worst;
}

// The largest angle, in degrees, between the normals n * 0.5 + 0.5 of two images.
double largestNormalAngle(const Image& a, const Image& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        glm::dvec3 na, nb;
        for (int c = 0; c < 3; ++c) {
            na[c] = a.rgba[i + size_t(c)] / 127.5 - 1.0;
            nb[c] = b.rgba[i + size_t(c)] / 127.5 - 1.0;
        }
        const double d = glm::dot(glm::normalize(na), glm::normalize(nb));
        worst = std::max(worst, std::acos(std::min(1.0, d)) * 180.0 / 3.141592653589793);
    }
    return worst;
}

} // namespace

namespace {

// Draws `decals` on the wall with the G-buffer blend (whose copy of the host's normals must be
// `normalCopy`), then with the DBuffer applied by the host, and compares the two.
void expectDBufferGivesTheBlend(const std::vector<Decal>& decals, const char* normalCopy) {
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    h->projector.setDecals(decals);
    const HostFrame f = h->host.frame(h->wall.camera, true);
    Result<ProjectorStats> blend = h->projector.draw(f);
    ASSERT_TRUE(blend.ok()) << blend.error();
    EXPECT_EQ(blend->normalCopy, normalCopy);
    const Image blendAlbedo = h->host.read(f.albedoTexture), blendNormal = h->host.read(f.normals.texture),
                blendMaterial = h->host.read(f.roughness.texture);

    h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
    const Image hostAlbedo = h->host.read(f.albedoTexture), hostNormal = h->host.read(f.normals.texture),
                hostMaterial = h->host.read(f.roughness.texture);
    ProjectorDraw dbuffer;
    dbuffer.path = ProjectorPath::DBuffer;
    Result<ProjectorStats> st = h->projector.draw(f, dbuffer);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->drawn, decals.size());
    EXPECT_THAT(st->variant, HasSubstr("DBUFFER"));
    EXPECT_EQ(st->normalCopy, "") << "the DBuffer reads the host's normals as they are";
    EXPECT_EQ(test::differingPixels(hostAlbedo, h->host.read(f.albedoTexture)), 0u)
        << "the G-buffer is read only";
    EXPECT_EQ(test::differingPixels(hostNormal, h->host.read(f.normals.texture)), 0u);
    EXPECT_EQ(test::differingPixels(hostMaterial, h->host.read(f.roughness.texture)), 0u);

    const Applied applied;
    applyDBuffer(f, h->projector.resources(), applied);
    const Image albedo = h->host.read(applied.albedo), normal = h->host.read(applied.normal),
                material = h->host.read(applied.material);
    ASSERT_GT(test::differingPixels(hostAlbedo, albedo), 100u) << "the decals show";
    const int albedoDiff = largestDifference(blendAlbedo, albedo, 0, 3);
    const int roughnessDiff = largestDifference(blendMaterial, material, 1, 2);
    const double normalAngle = largestNormalAngle(blendNormal, normal);
    std::printf("DBuffer applied vs G-buffer blend (%s normal copy): albedo %d/255, roughness %d/255, normal "
                "%.2f degrees\n",
                normalCopy, albedoDiff, roughnessDiff, normalAngle);
    // The blend rounds to 8 bits after each decal; the buffers round in their own formats and once more
    // when applied.
    EXPECT_LE(albedoDiff, 3);
    EXPECT_LE(roughnessDiff, 3);
    EXPECT_LE(normalAngle, 3.0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace

// A second decal over half of the wall's first: the buffers must compose decals in their order. The
// boxes are few and cover little of the view, so the blend copies the normals under each one's
// screen rectangle.
TEST(DBuffer, AppliedByTheHostGivesWhatTheGBufferBlendGives) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    std::vector<Decal> decals = wall.decals;
    decals.push_back(test::WallScene::decalAt(0, {-0.3f, 0.1f, 0.05f}));
    expectDBufferGivesTheBlend(decals, "rects");
}

// Two decals apart on the wall: each pixel is drawn by one box at most, so the blend reads and
// writes the host's normals in place, without a copy, and gives what the DBuffer gives.
TEST(DBuffer, AppliedByTheHostGivesWhatTheGBufferBlendGivesWithTheNormalsBlendedInPlace) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    std::vector<Decal> decals = {test::WallScene::decalAt(0, {-0.8f, 0.0f, 0.05f}),
                                 test::WallScene::decalAt(0, {0.5f, 0.3f, 0.05f})};
    for (Decal& d : decals)
        d.size = glm::vec2(0.9f);
    expectDBufferGivesTheBlend(decals, "in-place");
}

// Forty small overlapping decals: the blend copies the normals by drawing their boxes.
TEST(DBuffer, AppliedByTheHostGivesWhatTheGBufferBlendGivesUnderManyDecals) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    std::vector<Decal> decals = wall.decals;
    for (int i = 0; i < 40; ++i) {
        Decal d = test::WallScene::decalAt(0, {-0.9f + 0.03f * float(i), 0.1f * float(i % 4), 0.05f});
        d.size = glm::vec2(0.25f);
        decals.push_back(d);
    }
    expectDBufferGivesTheBlend(decals, "boxes");
}

// One decal over most of the view: the blend copies the whole viewport's normals.
TEST(DBuffer, AppliedByTheHostGivesWhatTheGBufferBlendGivesUnderALargeDecal) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    std::vector<Decal> decals = wall.decals;
    Decal large = test::WallScene::decalAt(0, {0.0f, 0.0f, 0.05f});
    large.size = glm::vec2(4.0f, 2.5f);
    decals.push_back(large);
    expectDBufferGivesTheBlend(decals, "viewport");
}

TEST(DBuffer, ReadsNoDecalAfterADrawWithNothingInView) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    ProjectorDraw dbuffer;
    dbuffer.path = ProjectorPath::DBuffer;
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), dbuffer).ok());
    const Image drawn = h->host.read(h->projector.resources().dbufferAlbedo);
    const Camera away = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 8.0});
    Result<ProjectorStats> st = h->projector.draw(h->host.frame(away, true), dbuffer);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_TRUE(st->skipped);
    size_t decalPixels = 0;
    for (size_t i = 3; i < drawn.rgba.size(); i += 4)
        decalPixels += drawn.rgba[i] < 255 ? 1 : 0;
    EXPECT_GT(decalPixels, 100u);
    const ProjectorResources r = h->projector.resources();
    for (const uint32_t t : {r.dbufferAlbedo, r.dbufferNormal, r.dbufferMaterial}) {
        const Image cleared = h->host.read(t);
        for (size_t i = 0; i < cleared.rgba.size(); i += 4)
            ASSERT_TRUE(cleared.rgba[i] == 0 && cleared.rgba[i + 1] == 0 && cleared.rgba[i + 2] == 0 &&
                        cleared.rgba[i + 3] == 255)
                << "texture " << t << " pixel " << i / 4;
    }
}

TEST(DBuffer, NeedsNoAlbedoTargetWhileTheBlendDoes) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    HostFrame f = h->host.frame(h->wall.camera, true);
    f.albedoTexture = 0;
    f.roughness = {};
    Result<ProjectorStats> blend = h->projector.draw(f);
    ASSERT_FALSE(blend.ok());
    EXPECT_THAT(blend.error(), HasSubstr("HostFrame.albedoTexture"));
    ProjectorDraw dbuffer;
    dbuffer.path = ProjectorPath::DBuffer;
    Result<ProjectorStats> st = h->projector.draw(f, dbuffer);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->drawn, 2u);
    EXPECT_FALSE(DecalProjector::hostShader("nonsense.glsl").ok());
}
