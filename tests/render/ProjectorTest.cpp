// The projector's host contract (spatter/render/DecalProjector.hpp): the GL state it promises to
// leave as it found it, host descriptions that do not fit, and the same decals in a foreign host
// and in spatter's renderer.

#include "ForeignHost.hpp"
#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/render/DecalProjector.hpp"
#include "spatter/render/DecalTextures.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

// Every piece of GL state the header lists, as numbers.
std::vector<int64_t> glStateSnapshot() {
    std::vector<int64_t> v;
    auto get = [&v](GLenum name, int count = 1) {
        GLint64 x[4] = {0, 0, 0, 0};
        glGetInteger64v(name, x);
        v.insert(v.end(), x, x + count);
    };
    auto getIndexed = [&v](GLenum name, GLuint index) {
        GLint64 x = 0;
        glGetInteger64i_v(name, index, &x);
        v.push_back(x);
    };
    get(GL_DRAW_FRAMEBUFFER_BINDING);
    get(GL_READ_FRAMEBUFFER_BINDING);
    get(GL_CURRENT_PROGRAM);
    get(GL_VERTEX_ARRAY_BINDING);
    get(GL_VIEWPORT, 4);
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    v.push_back(active);
    for (GLuint unit = 0; unit < 8; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        get(GL_TEXTURE_BINDING_2D);
        get(GL_TEXTURE_BINDING_2D_ARRAY);
        get(GL_SAMPLER_BINDING);
    }
    glActiveTexture(GLenum(active));
    for (GLuint i = 0; i < 2; ++i)
        for (GLenum name : {GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE})
            getIndexed(name, i);
    for (GLuint i = 0; i < 11; ++i)
        for (GLenum name : {GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                            GL_SHADER_STORAGE_BUFFER_SIZE})
            getIndexed(name, i);
    for (GLenum name : {GL_UNIFORM_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_BINDING, GL_ARRAY_BUFFER_BINDING,
                        GL_PIXEL_UNPACK_BUFFER_BINDING, GL_DRAW_INDIRECT_BUFFER_BINDING,
                        GL_DISPATCH_INDIRECT_BUFFER_BINDING})
        get(name);
    for (GLuint i = 0; i < 3; ++i)
        for (GLenum name : {GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED,
                            GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT})
            getIndexed(name, i);
    for (GLuint i = 0; i < 4; ++i) {
        v.push_back(glIsEnabledi(GL_BLEND, i));
        for (GLenum name : {GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA,
                            GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA})
            getIndexed(name, i);
        GLboolean mask[4];
        glGetBooleani_v(GL_COLOR_WRITEMASK, i, mask);
        v.insert(v.end(), mask, mask + 4);
    }
    for (GLenum cap :
         {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_SCISSOR_TEST, GL_CULL_FACE, GL_FRAMEBUFFER_SRGB,
          GL_RASTERIZER_DISCARD, GL_COLOR_LOGIC_OP, GL_DEPTH_CLAMP, GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE7})
        v.push_back(glIsEnabled(cap));
    get(GL_POLYGON_MODE, 2);
    for (GLenum name : {GL_DEPTH_WRITEMASK, GL_DEPTH_FUNC, GL_CULL_FACE_MODE, GL_FRONT_FACE, GL_CLIP_ORIGIN,
                        GL_CLIP_DEPTH_MODE, GL_UNPACK_ALIGNMENT})
        get(name);
    return v;
}

// GL objects a host has bound, and unusual values for all the state the header lists.
struct HostState {
    GLuint fbo = 0, program = 0, vao = 0, sampler = 0, buffers[4] = {0, 0, 0, 0}, textures[3] = {0, 0, 0};

    HostState() {
        glCreateFramebuffers(1, &fbo);
        program = glCreateProgram();
        const char* text = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
        const GLuint vs = glCreateShader(GL_VERTEX_SHADER);
        glShaderSource(vs, 1, &text, nullptr);
        glCompileShader(vs);
        glAttachShader(program, vs);
        glLinkProgram(program);
        glDeleteShader(vs);
        glCreateVertexArrays(1, &vao);
        glCreateSamplers(1, &sampler);
        glCreateBuffers(4, buffers);
        for (GLuint b : buffers)
            glNamedBufferStorage(b, 1024, nullptr, 0);
        glCreateTextures(GL_TEXTURE_2D, 2, textures);
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, textures + 2);
        glTextureStorage2D(textures[0], 1, GL_RGBA8, 4, 4);
        glTextureStorage2D(textures[1], 1, GL_R32F, 4, 4);
        glTextureStorage3D(textures[2], 1, GL_RGBA8, 4, 4, 2);
    }
    // Back to GL's defaults for the tests that follow on the shared context.
    ~HostState() {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glUseProgram(0);
        glBindVertexArray(0);
        glBindSampler(2, 0);
        glActiveTexture(GL_TEXTURE0);
        for (GLuint i = 0; i < 4; ++i) {
            glBlendFuncSeparatei(i, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
            glBlendEquationSeparatei(i, GL_FUNC_ADD, GL_FUNC_ADD);
            glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDisable(GL_RASTERIZER_DISCARD);
        glDisable(GL_COLOR_LOGIC_OP);
        glDisable(GL_DEPTH_CLAMP);
        glDisable(GL_CLIP_DISTANCE0);
        glDisable(GL_CLIP_DISTANCE7);
        glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
        glBindImageTexture(2, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
        glDeleteFramebuffers(1, &fbo);
        glDeleteProgram(program);
        glDeleteVertexArrays(1, &vao);
        glDeleteSamplers(1, &sampler);
        glDeleteBuffers(4, buffers);
        glDeleteTextures(3, textures);
    }

    void apply() const {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glUseProgram(program);
        glBindVertexArray(vao);
        glViewport(3, 5, 17, 11);
        glBindImageTexture(1, textures[1], 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
        glBindImageTexture(2, textures[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        for (GLuint unit = 0; unit < 8; ++unit) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glBindTexture(GL_TEXTURE_2D, textures[unit % 2]);
            glBindTexture(GL_TEXTURE_2D_ARRAY, textures[2]);
        }
        glBindSampler(2, sampler);
        glActiveTexture(GL_TEXTURE5);
        glBindBufferRange(GL_UNIFORM_BUFFER, 0, buffers[0], 256, 512);
        glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffers[1]);
        for (GLuint i = 0; i < 11; ++i)
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, buffers[i % 4], 0, 256);
        glBindBuffer(GL_UNIFORM_BUFFER, buffers[2]);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[3]);
        glBindBuffer(GL_ARRAY_BUFFER, buffers[1]);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffers[2]);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, buffers[1]);
        for (GLuint i = 0; i < 4; ++i) {
            if (i % 2)
                glEnablei(GL_BLEND, i);
            else
                glDisablei(GL_BLEND, i);
            glBlendFuncSeparatei(i, GL_ONE, GL_DST_COLOR, GL_ZERO, GL_SRC_ALPHA_SATURATE);
            glBlendEquationSeparatei(i, GL_MAX, GL_FUNC_REVERSE_SUBTRACT);
            glColorMaski(i, GL_FALSE, GL_TRUE, i == 2, GL_TRUE);
        }
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_FALSE);
        glEnable(GL_STENCIL_TEST);
        glEnable(GL_SCISSOR_TEST);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT_AND_BACK);
        glFrontFace(GL_CW);
        glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_FRAMEBUFFER_SRGB);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
        // State that would spoil the projector's draws if it kept it.
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glEnable(GL_RASTERIZER_DISCARD);
        glEnable(GL_COLOR_LOGIC_OP);
        glEnable(GL_DEPTH_CLAMP);
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE7);
    }
};

} // namespace

TEST(Projector, LeavesEveryListedGlStateAsItFoundIt) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    const Image albedoBefore = h->host.read(h->host.albedoTexture());
    const HostState state;
    state.apply();
    const std::vector<int64_t> before = glStateSnapshot();
    Result<ProjectorStats> blended = h->projector.draw(h->host.frame(h->wall.camera, true));
    ASSERT_TRUE(blended.ok()) << blended.error();
    EXPECT_EQ(blended->drawn, 2u);
    // The host's state did not spoil the draw (line polygons, rasterizer discard, logic op...).
    EXPECT_GT(test::differingPixels(albedoBefore, h->host.read(h->host.albedoTexture())), 20u);
    EXPECT_EQ(glStateSnapshot(), before) << "after a blended draw";
    HostFrame alphaRoughness = h->host.frame(h->wall.camera, true);
    alphaRoughness.roughness = {alphaRoughness.albedoTexture, 3};
    ASSERT_TRUE(h->projector.draw(alphaRoughness).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after a draw with roughness in an alpha channel";
    ProjectorDraw coverage;
    coverage.coverageTexture = h->host.coverageTexture();
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), coverage).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after a coverage draw";
    ProjectorDraw dbuffer;
    dbuffer.path = ProjectorPath::DBuffer;
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), dbuffer).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after a DBuffer draw";
    ASSERT_TRUE(h->projector.bin(h->host.forwardFrame(h->wall.camera)).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after binning for the forward path";
    ASSERT_TRUE(h->projector.addDecalTexture(makeBuiltinDecalTexture(DecalTexture::Blood, 32).albedo).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after addDecalTexture";
    Result<uint64_t> search =
        h->projector.findSurface(h->host.frame(h->wall.camera, true), {{{0.0, 1.0, 0.3}, {0.0, 1.0, -0.3}}});
    ASSERT_TRUE(search.ok()) << search.error();
    ASSERT_TRUE(h->projector.surfaceFound(search.value(), true).has_value());
    EXPECT_EQ(glStateSnapshot(), before) << "after a search of the drawn surface";
    HostFrame bad = h->host.frame(h->wall.camera, true);
    bad.projection = glm::dmat4(0.0);
    EXPECT_FALSE(h->projector.draw(bad).ok());
    EXPECT_EQ(glStateSnapshot(), before) << "after a failed draw";
    ProjectorSettings compute;
    compute.deferredResolve = DeferredResolve::Compute;
    compute.gpuCullingFrom = 0; // the culling's and the binning's passes and their read-backs too
    Result<DecalProjector> resolver = DecalProjector::create(compute);
    ASSERT_TRUE(resolver.ok()) << resolver.error();
    ASSERT_TRUE(resolver->setObjects(h->wall.transforms, h->wall.ids).ok());
    resolver->setDecalTypes(h->wall.types);
    resolver->setDecals(h->wall.decals);
    Result<ProjectorStats> resolved = resolver->draw(h->host.frame(h->wall.camera, true));
    ASSERT_TRUE(resolved.ok()) << resolved.error();
    EXPECT_NE(resolved->variant.find("COMPUTE"), std::string::npos) << resolved->variant;
    EXPECT_EQ(glStateSnapshot(), before) << "after a draw resolved in one compute pass";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST(Projector, BlendsIntoTheHostsTargetsAndClipsByObjectId) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    const Image before = h->host.read(h->host.albedoTexture());
    Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->drawn, 2u) << "culled " << st->culled << ", invalid " << st->invalid;
    EXPECT_THAT(st->variant, HasSubstr("IDS"));
    EXPECT_THAT(st->variant, HasSubstr("CLIP_MINUS_ONE"));
    EXPECT_THAT(st->variant, HasSubstr("STANDARD_Z"));
    EXPECT_THAT(st->variant, HasSubstr("NORMAL_WORLD_UNORM"));
    const Image after = h->host.read(h->host.albedoTexture());
    EXPECT_GT(test::differingPixels(before, after), 20u); // the paint texture is opaque only in places
    // Coverage with and without the ID texture: the crate's decal reaches the wall behind it only
    // without IDs.
    ProjectorDraw draw;
    draw.coverageTexture = h->host.coverageTexture();
    h->host.clearCoverage();
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), draw).ok());
    const size_t withIds = test::countSet(test::whiteMask(h->host.read(h->host.coverageTexture())));
    h->host.clearCoverage();
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, false), draw).ok());
    const size_t withoutIds = test::countSet(test::whiteMask(h->host.read(h->host.coverageTexture())));
    EXPECT_GT(withIds, 0u);
    EXPECT_GT(withoutIds, withIds);
}

// Without its pass timer (ProjectorSettings::passTimer off) the projector blends the same albedo and
// reports no GPU time, where the timed one reports this draw's (waitForTimers).
TEST(Projector, BlendsTheSameWithoutItsPassTimerAndReportsNoGpuTime) {
    SPATTER_REQUIRE_GL(gl);
    ProjectorSettings timed;
    timed.waitForTimers = true;
    ProjectorSettings untimed = timed;
    untimed.passTimer = false;
    std::vector<Image> albedo;
    for (const ProjectorSettings& settings : {timed, untimed}) {
        std::optional<test::HostedWall> h = test::HostedWall::make(settings);
        ASSERT_TRUE(h);
        for (int draw = 0; draw < 2; ++draw) {
            Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
            ASSERT_TRUE(st.ok()) << st.error();
            EXPECT_EQ(st->drawn, 2u);
            EXPECT_EQ(st->gpuFrame, settings.passTimer ? int64_t(draw) : int64_t(-1));
            EXPECT_TRUE(settings.passTimer || st->gpuMs == 0.0) << st->gpuMs;
        }
        albedo.push_back(h->host.read(h->host.albedoTexture()));
    }
    EXPECT_EQ(test::differingPixels(albedo[0], albedo[1]), 0u);
}

// Without restoring the GL state (ProjectorSettings::restoreGlState off) the projector blends the same
// albedo, and leaves its own program bound where the restoring one leaves the host's: it saved nothing.
TEST(Projector, BlendsTheSameWithoutRestoringTheGlStateAndLeavesItsOwn) {
    SPATTER_REQUIRE_GL(gl);
    ProjectorSettings leaving;
    leaving.restoreGlState = false;
    std::vector<Image> albedo;
    for (const ProjectorSettings& settings : {ProjectorSettings{}, leaving}) {
        std::optional<test::HostedWall> h = test::HostedWall::make(settings);
        ASSERT_TRUE(h);
        glUseProgram(0);
        Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
        ASSERT_TRUE(st.ok()) << st.error();
        EXPECT_EQ(st->drawn, 2u);
        GLint program = -1;
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        EXPECT_EQ(program != 0, !settings.restoreGlState) << program;
        albedo.push_back(h->host.read(h->host.albedoTexture()));
    }
    EXPECT_EQ(test::differingPixels(albedo[0], albedo[1]), 0u);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// A decal clips to the decal ID the host gives its object (setObjects), not to the one it carries:
// the crate's decal covers the same pixels whatever its own ID says, and once the crate's ID changes
// in the host's frame and in setObjects alike it follows.
TEST(Projector, ClipsADecalToItsObjectsIdNotItsOwn) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    auto covered = [&](const std::vector<uint8_t>& ids) {
        h->host.draw(h->wall.transforms, ids, h->wall.camera);
        EXPECT_TRUE(h->projector.setObjects(h->wall.transforms, ids).ok());
        ProjectorDraw draw;
        draw.coverageTexture = h->host.coverageTexture();
        h->host.clearCoverage();
        EXPECT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), draw).ok());
        return test::whiteMask(h->host.read(h->host.coverageTexture()));
    };
    const std::vector<uint8_t> asPlaced = covered(h->wall.ids);
    std::vector<Decal> ownIdsWrong = h->wall.decals;
    for (Decal& d : ownIdsWrong)
        d.objectId = uint8_t(d.objectId + 40);
    h->projector.setDecals(ownIdsWrong);
    EXPECT_EQ(covered(h->wall.ids), asPlaced);
    std::vector<uint8_t> renamed = h->wall.ids;
    renamed[1] = 99;
    EXPECT_EQ(covered(renamed), asPlaced);
    EXPECT_GT(test::countSet(asPlaced), 0u);
}

TEST(Projector, RejectsHostFramesThatDoNotFitNamingTheFieldAndDrawsNothing) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    const HostFrame good = h->host.frame(h->wall.camera, true);
    ASSERT_EQ(h->projector.frameProblem(good), "");
    struct Textures {
        GLuint rgba8 = 0, narrow = 0, r32f = 0; // the frame's size in RGBA8 and R32F, half as wide
    } t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t.rgba8);
    glTextureStorage2D(t.rgba8, 1, GL_RGBA8, kWallWidth, kWallHeight);
    glCreateTextures(GL_TEXTURE_2D, 1, &t.narrow);
    glTextureStorage2D(t.narrow, 1, GL_RGBA8, kWallWidth / 2, kWallHeight);
    glCreateTextures(GL_TEXTURE_2D, 1, &t.r32f);
    glTextureStorage2D(t.r32f, 1, GL_R32F, kWallWidth, kWallHeight);
    struct Case {
        const char* field;
        void (*change)(HostFrame&, const Textures&);
    };
    const Case cases[] = {
        {"HostFrame.depth.texture", [](HostFrame& f, const Textures&) { f.depth.texture = 0; }},
        {"HostFrame.albedoTexture", [](HostFrame& f, const Textures&) { f.albedoTexture = 0; }},
        {"HostFrame.albedoTexture", [](HostFrame& f, const Textures& x) { f.albedoTexture = x.narrow; }},
        {"HostFrame.albedoTexture", [](HostFrame& f, const Textures& x) { f.albedoTexture = x.r32f; }},
        {"HostFrame.normals.texture",
         [](HostFrame& f, const Textures& x) {
             f.normals = {x.rgba8, NormalEncoding::WorldSigned};
         }},
        {"HostFrame.objectIdTexture", [](HostFrame& f, const Textures& x) { f.objectIdTexture = x.rgba8; }},
        {"HostFrame.faceNormalTexture",
         [](HostFrame& f, const Textures& x) { f.faceNormalTexture = x.r32f; }},
        {"HostFrame.faceNormalTexture",
         [](HostFrame& f, const Textures& x) { f.faceNormalTexture = x.narrow; }},
        {"HostFrame.roughness.channel", [](HostFrame& f, const Textures&) { f.roughness.channel = 4; }},
        {"HostFrame.roughness.texture",
         [](HostFrame& f, const Textures&) { f.roughness.texture = f.albedoTexture; }},
        {"HostFrame.projection", [](HostFrame& f, const Textures&) { f.projection = glm::dmat4(0.0); }},
        {"HostFrame.view",
         [](HostFrame& f, const Textures&) { f.view[0][0] = std::numeric_limits<double>::quiet_NaN(); }},
        {"HostFrame.depth.reversedZ", [](HostFrame& f, const Textures&) { f.depth.reversedZ = true; }},
        {"HostFrame.depth.texture",
         [](HostFrame& f, const Textures& x) {
             f.depth = {x.rgba8, DepthEncoding::LinearView, ClipDepth::ZeroToOne, false};
         }},
        {"HostFrame viewport", [](HostFrame& f, const Textures&) { f.width = 0; }},
        {"HostFrame.depth.texture", [](HostFrame& f, const Textures&) { f.x = 1; }},
        {"HostFrame.depth.texture", // x + width past the largest int
         [](HostFrame& f, const Textures&) {
             f.x = std::numeric_limits<int>::max();
             f.width = 1;
         }},
        {"HostFrame.albedoTexture: the same texture as HostFrame.depth.texture",
         [](HostFrame& f, const Textures&) { f.depth.texture = f.albedoTexture; }},
        {"HostFrame.normals.texture: the same texture as HostFrame.depth.texture",
         [](HostFrame& f, const Textures&) { f.depth.texture = f.normals.texture; }},
    };
    const Image before = h->host.read(h->host.albedoTexture());
    for (const Case& c : cases) {
        HostFrame f = good;
        c.change(f, t);
        Result<ProjectorStats> st = h->projector.draw(f);
        ASSERT_FALSE(st.ok()) << c.field;
        EXPECT_THAT(st.error(), HasSubstr(c.field));
    }
    ProjectorDraw nowhere;
    nowhere.path = ProjectorPath(7);
    Result<ProjectorStats> st = h->projector.draw(good, nowhere);
    ASSERT_FALSE(st.ok());
    EXPECT_THAT(st.error(), HasSubstr("ProjectorDraw.path 7"));
    EXPECT_EQ(test::differingPixels(before, h->host.read(h->host.albedoTexture())), 0u);
    const GLuint textures[3] = {t.rgba8, t.narrow, t.r32f};
    glDeleteTextures(3, textures);
    EXPECT_FALSE(h->projector.setObjects(h->wall.transforms, {0}).ok());
}

// The same decals on the same grey (0.5) wall and crate, in spatter's renderer (an sRGB albedo
// target, reversed Z, octahedral normals) and in the foreign host (linear RGBA8, standard Z, RGB10A2
// normals): under the decals the albedo agrees, in linear terms, within 2/255 on average and 8/255
// at most, the quantisation of the two targets' 8-bit encodings.
TEST(Projector, TheSameDecalsGiveTheSameAlbedoInEveryHost) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    Scene scene = h->wall.scene;
    Material grey;
    grey.name = "grey";
    grey.baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    scene.materials = {grey};
    for (SceneObject& o : scene.objects)
        o.editMesh().submeshes = {{0, uint32_t(o.mesh->indices.size()), 0}};
    Result<Renderer> r = test::makeRenderer(kWallWidth, kWallHeight);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setObjectIds(h->wall.ids).ok());
    r->setDecalTypes(h->wall.types);
    r->setDecals(h->wall.decals);
    const Image spatterAlbedo = test::renderView(r.value(), h->wall.camera, View::Albedo);

    h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true)).ok());
    const Image hostAlbedo = h->host.read(h->host.albedoTexture());
    ProjectorDraw coverage;
    coverage.coverageTexture = h->host.coverageTexture();
    h->host.clearCoverage();
    ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true), coverage).ok());
    const std::vector<uint8_t> decalPixels = test::whiteMask(h->host.read(h->host.coverageTexture()));
    ASSERT_GT(test::countSet(decalPixels), 100u);

    auto srgbToLinear = [](uint8_t v) {
        const double c = v / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    double sum = 0.0, worst = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < decalPixels.size(); ++p) {
        if (!decalPixels[p]) continue;
        for (int c = 0; c < 3; ++c) {
            const double a = srgbToLinear(spatterAlbedo.rgba[p * 4 + size_t(c)]);
            const double b = hostAlbedo.rgba[p * 4 + size_t(c)] / 255.0;
            sum += std::fabs(a - b);
            worst = std::max(worst, std::fabs(a - b));
            ++n;
        }
    }
    std::printf("albedo under %zu decal pixels: mean difference %.2f/255, largest %.2f/255\n", n / 3,
                255.0 * sum / double(n), 255.0 * worst);
    EXPECT_LE(255.0 * sum / double(n), 2.0);
    EXPECT_LE(255.0 * worst, 8.0);
}

// Roughness in the albedo texture's alpha channel (a second draw of the boxes with dual-source
// blending): under the decals alpha moves towards the type's roughness (0.2) while the colour is
// blended as usual; elsewhere both stay.
TEST(Projector, WritesRoughnessIntoTheAlbedoAlphaChannel) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    const Image before = h->host.read(h->host.albedoTexture());
    HostFrame f = h->host.frame(h->wall.camera, true);
    f.roughness = {f.albedoTexture, 3};
    Result<ProjectorStats> st = h->projector.draw(f);
    ASSERT_TRUE(st.ok()) << st.error();
    // The normals copied under the boxes' rectangles, the blend, then the alpha roughness pass (no box
    // holds the eye).
    EXPECT_EQ(st->normalCopy, "rects");
    EXPECT_EQ(st->drawCalls, 2u);
    const Image after = h->host.read(h->host.albedoTexture());
    size_t rougher = 0, colourOnly = 0, alphaOnly = 0;
    for (size_t i = 0; i < after.rgba.size(); i += 4) {
        const bool colour = std::memcmp(&before.rgba[i], &after.rgba[i], 3) != 0;
        const bool alpha = before.rgba[i + 3] != after.rgba[i + 3];
        rougher += alpha && after.rgba[i + 3] < before.rgba[i + 3] ? 1 : 0;
        colourOnly += colour && !alpha ? 1 : 0;
        alphaOnly += alpha && !colour ? 1 : 0;
    }
    EXPECT_GT(rougher, 20u);
    // Where the decal's alpha rounds the colour away, its roughness can still show, and the reverse.
    EXPECT_LT(colourOnly + alphaOnly, rougher);
    std::printf("alpha roughness: %zu pixels rougher, %zu colour only, %zu alpha only\n", rougher, colourOnly,
                alphaOnly);
}

namespace {

// A 64 x 64 frame of a wall at z = 0 seen from z = 2, its depth given as `depth` (a constant the
// test computes for each encoding), and the coverage of a 1 x 1 decal at the origin in it.
size_t wallCoverage(const glm::dmat4& projection, HostDepth depth, float depthValue) {
    constexpr int kSize = 64;
    auto texture = [](GLenum format) {
        GLuint t = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &t);
        glTextureStorage2D(t, 1, format, kSize, kSize);
        return t;
    };
    const bool depthFormat = depth.encoding == DepthEncoding::Window;
    depth.texture = texture(depthFormat ? GL_DEPTH_COMPONENT32F : GL_R32F);
    glClearTexImage(depth.texture, 0, depthFormat ? GL_DEPTH_COMPONENT : GL_RED, GL_FLOAT, &depthValue);
    const GLuint coverage = texture(GL_R8), albedo = texture(GL_RGBA8);
    const unsigned char black[4] = {0, 0, 0, 0};
    glClearTexImage(coverage, 0, GL_RGBA, GL_UNSIGNED_BYTE, black);
    Result<DecalProjector> projector = DecalProjector::create();
    EXPECT_TRUE(projector.ok());
    DecalType t;
    t.name = "square";
    projector->setDecalTypes({t});
    EXPECT_TRUE(projector->setObjects({glm::dmat4(1.0)}, {0}).ok());
    projector->setDecals({test::WallScene::decalAt(0, glm::vec3(0.0f))});
    HostFrame f;
    f.width = f.height = kSize;
    f.view = glm::lookAt(glm::dvec3(0, 0, 2), glm::dvec3(0.0), glm::dvec3(0, 1, 0));
    f.projection = projection;
    f.eye = glm::dvec3(0, 0, 2);
    f.depth = depth;
    f.albedoTexture = albedo;
    ProjectorDraw draw;
    draw.coverageTexture = coverage;
    Result<ProjectorStats> st = projector->draw(f, draw);
    EXPECT_TRUE(st.ok()) << st.error();
    std::vector<uint8_t> pixels(size_t(kSize) * kSize * 4);
    glGetTextureImage(coverage, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    const GLuint textures[3] = {depth.texture, coverage, albedo};
    glDeleteTextures(3, textures);
    size_t n = 0;
    for (size_t i = 0; i < pixels.size(); i += 4)
        n += pixels[i] > 127 ? 1 : 0;
    return n;
}

} // namespace

// One wall, one decal, every depth convention: window depth in either clip range and direction,
// linear view depth, perspective and orthographic projections. The 0.6-unit decal covers what its
// size predicts, to the pixel rows its edges cross.
TEST(Projector, EveryDepthConventionRebuildsTheSameSurface) {
    SPATTER_REQUIRE_GL(gl);
    const double near = 0.1, far = 100.0;
    const glm::dmat4 perspective = glm::perspective(glm::radians(60.0), 1.0, near, far);
    // The wall's window depth under GL's default clip range, and under the zero-to-one range.
    const glm::dvec4 clip = perspective * glm::dvec4(0.0, 0.0, -2.0, 1.0);
    const float minusOneToOne = float(clip.z / clip.w * 0.5 + 0.5);
    glm::dmat4 zeroToOne = perspective; // the same frustum with depth from 0 (near) to 1 (far)
    zeroToOne[2][2] = -far / (far - near);
    zeroToOne[3][2] = -far * near / (far - near);
    const glm::dvec4 clip01 = zeroToOne * glm::dvec4(0.0, 0.0, -2.0, 1.0);
    glm::dmat4 reversed = zeroToOne; // reversed: 1 at the near plane, 0 at the far one
    reversed[2][2] = near / (far - near);
    reversed[3][2] = far * near / (far - near);
    const glm::dvec4 clipRev = reversed * glm::dvec4(0.0, 0.0, -2.0, 1.0);
    // 0.6 of the 2 * 2 tan(30 deg) view: a square of about 16.6 pixels.
    const double side = 0.6 / (4.0 * std::tan(glm::radians(30.0))) * 64.0;
    const size_t expected = size_t(side * side);
    const size_t standard =
        wallCoverage(perspective, {0, DepthEncoding::Window, ClipDepth::MinusOneToOne, false}, minusOneToOne);
    const size_t standard01 = wallCoverage(zeroToOne, {0, DepthEncoding::Window, ClipDepth::ZeroToOne, false},
                                           float(clip01.z / clip01.w));
    const size_t reversedZ = wallCoverage(reversed, {0, DepthEncoding::Window, ClipDepth::ZeroToOne, true},
                                          float(clipRev.z / clipRev.w));
    const size_t linear =
        wallCoverage(perspective, {0, DepthEncoding::LinearView, ClipDepth::ZeroToOne, false}, 2.0f);
    for (size_t n : {standard, standard01, reversedZ, linear})
        EXPECT_NEAR(double(n), double(expected), 2.0 * side + 2.0) << "expected about " << expected;
    // Orthographic, 2 x 2 units in view: the decal covers 0.3 of each side.
    const glm::dmat4 ortho = glm::ortho(-1.0, 1.0, -1.0, 1.0, near, far);
    const glm::dvec4 clipOrtho = ortho * glm::dvec4(0.0, 0.0, -2.0, 1.0);
    const size_t orthographic = wallCoverage(
        ortho, {0, DepthEncoding::Window, ClipDepth::MinusOneToOne, false}, float(clipOrtho.z * 0.5 + 0.5));
    const size_t orthoLinear =
        wallCoverage(ortho, {0, DepthEncoding::LinearView, ClipDepth::MinusOneToOne, false}, 2.0f);
    const double orthoSide = 0.3 * 64.0;
    for (size_t n : {orthographic, orthoLinear})
        EXPECT_NEAR(double(n), orthoSide * orthoSide, 2.0 * orthoSide + 2.0);
    std::printf(
        "coverage: standard %zu, standard 0..1 %zu, reversed %zu, linear %zu, ortho %zu, ortho linear %zu "
        "(expected %zu and %.0f)\n",
        standard, standard01, reversedZ, linear, orthographic, orthoLinear, expected, orthoSide * orthoSide);
}

// The copy of the host's normals that decals writing normals read is held while draws read it:
// ProjectorMemory::kNormalCopyIdleDraws draws of decals that write none free it, and the next draw
// that needs it makes it again and blends as a projector that never freed it.
TEST(Projector, FreesTheCopyOfTheHostsNormalsOnceItsDrawsStopReadingIt) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    // Two overlapping decals: their boxes read normals the other writes, so the draw takes a copy.
    std::vector<Decal> decals = h->wall.decals;
    decals.push_back(test::WallScene::decalAt(0, {-0.4f, 0.2f, 0.05f}));
    h->projector.setDecals(decals);
    auto drawNormals = [&]() -> std::optional<Image> {
        h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
        Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
        EXPECT_TRUE(st.ok()) << st.error();
        if (!st) return std::nullopt;
        return h->host.read(h->host.frame(h->wall.camera, true).normals.texture);
    };
    const std::optional<Image> first = drawNormals();
    ASSERT_TRUE(first);
    const size_t copy = h->projector.memory().gpuScreenBytes;
    EXPECT_EQ(copy, size_t(test::kWallWidth) * test::kWallHeight * 4);

    std::vector<DecalType> plain = h->wall.types;
    plain[0].normalMap = false;
    h->projector.setDecalTypes(plain);
    for (int i = 1; i < ProjectorMemory::kNormalCopyIdleDraws; ++i)
        ASSERT_TRUE(drawNormals());
    EXPECT_EQ(h->projector.memory().gpuScreenBytes, copy) << "freed before the draws in a row";
    ASSERT_TRUE(drawNormals());
    EXPECT_EQ(h->projector.memory().gpuScreenBytes, 0u);

    h->projector.setDecalTypes(h->wall.types);
    const std::optional<Image> again = drawNormals();
    ASSERT_TRUE(again);
    EXPECT_EQ(h->projector.memory().gpuScreenBytes, copy);
    EXPECT_EQ(test::differingPixels(*first, *again), 0u);
}
