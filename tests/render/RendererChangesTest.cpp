// spatter's renderer fed the decal system's change list (updateDecals) while it draws some decals
// itself: volumetric types as craters and the decals of a texture-space object as splats. Frame by
// frame it draws exactly what a renderer given every decal (setDecals) draws, with the same counts,
// through spawns, removals, evictions and fades, and it uploads only the records that changed.

#include "RenderTestSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <optional>
#include <string>

using namespace spatter;

namespace {

constexpr int kChangesW = 96;
constexpr int kChangesH = 72;

// A floor of two objects: a projected slab at x < 0 and a texture-space sheet (a grid, UVs in [0, 1]
// without overlap) at x > 0.
Scene slabAndSheetScene() {
    Scene s;
    Material grey;
    grey.name = "grey";
    grey.baseColorFactor = glm::vec4(0.3f, 0.3f, 0.3f, 1.0f);
    s.materials.push_back(grey);
    Mesh box = makeBox(glm::vec3(1.0f, 0.2f, 1.0f), 2);
    Mesh grid = makeGrid(makeSamples(0.0f, 2.0f, 0.25f), makeSamples(-1.0f, 1.0f, 0.25f));
    for (glm::vec2& uv : grid.uvs)
        uv = {uv.x * 0.5f, uv.y * 0.5f + 0.5f};
    computeTangents(grid);
    for (Mesh* m : {&box, &grid})
        m->submeshes = {{0, uint32_t(m->indices.size()), 0}};
    SceneObject slab =
        makeSceneObject("slab", std::move(box), glm::translate(glm::dmat4(1.0), glm::dvec3(-1.0, -0.2, 0.0)));
    SceneObject sheet = makeSceneObject("sheet", std::move(grid));
    s.objects.push_back(std::move(slab));
    s.objects.push_back(std::move(sheet));
    return s;
}

std::vector<DecalType> decalTypes() {
    DecalType paint;
    paint.name = "paint";
    paint.size = glm::vec2(0.3f);
    paint.texture = int(DecalTexture::Paint);
    DecalType fading = paint;
    fading.name = "fading";
    fading.texture = int(DecalTexture::Blood);
    fading.lifetime = 0.6f;
    fading.fadeOutTime = 0.3f;
    DecalType crater;
    crater.name = "crater";
    crater.size = glm::vec2(0.25f);
    crater.volumetric = true;
    return {paint, fading, crater};
}

struct Pair {
    std::optional<Renderer> changes, whole; // fed updateDecals, and setDecals every frame
    std::optional<DecalSystem> sys;
    uint64_t version = 0;
};

std::optional<Pair> makePair() {
    Pair p;
    const Scene scene = slabAndSheetScene();
    for (std::optional<Renderer>* r : {&p.changes, &p.whole}) {
        Result<Renderer> made = test::makeRenderer(kChangesW, kChangesH);
        EXPECT_TRUE(made.ok()) << made.error();
        if (!made) return std::nullopt;
        r->emplace(std::move(made).value());
        EXPECT_TRUE((*r)->setScene(scene).ok());
        EXPECT_TRUE((*r)->setObjectDecalMode(1, DecalMode::TextureSpace, 256).ok());
        (*r)->setDecalTypes(decalTypes());
    }
    DecalSettings settings;
    settings.budget = 40; // evictions from the third frame on
    Result<DecalSystem> sys = DecalSystem::create(scene, settings);
    EXPECT_TRUE(sys.ok()) << sys.error();
    if (!sys) return std::nullopt;
    p.sys.emplace(std::move(sys).value());
    for (const DecalType& t : decalTypes())
        EXPECT_TRUE(p.sys->registerType(t).ok());
    return p;
}

// A few spawns of each type at random points of the floor, a removal, and time passing.
void play(Pair& p, Rng& rng, std::deque<DecalHandle>& handles) {
    for (int k = 0; k < 6; ++k) {
        const uint32_t object = rng.below(2);
        const glm::vec3 at(object == 0 ? rng.uniform(-0.8f, 0.8f) : rng.uniform(0.2f, 1.8f),
                           object == 0 ? 0.2f : 0.0f, rng.uniform(-0.8f, 0.8f));
        const SpawnResult r = p.sys->spawnAttached(object, at, glm::vec3(0, 1, 0), uint16_t(rng.below(3)));
        if (r.placed()) handles.push_back(r.handle);
        // Decals of one spawn time draw in the order they reached the projector: by index when taken
        // whole, in spawn order through the change list. Apart in time, both agree.
        ASSERT_TRUE(p.sys->update(0.01).ok());
    }
    if (handles.size() > 4) {
        p.sys->remove(handles[rng.below(uint32_t(handles.size()))]);
        handles.pop_front();
    }
    ASSERT_TRUE(p.sys->update(0.25).ok());
}

// "" when the images are equal, else how many pixels differ and where the first is.
std::string imageDifference(const Image& a, const Image& b) {
    if (a.rgba.size() != b.rgba.size()) return "images of different sizes";
    size_t differ = 0, first = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        if (std::memcmp(&a.rgba[i], &b.rgba[i], 4) != 0 && differ++ == 0) first = i / 4;
    if (differ == 0) return "";
    return std::to_string(differ) + " pixels differ, the first at (" +
           std::to_string(first % size_t(a.width)) + ", " + std::to_string(first / size_t(a.width)) + ")";
}

Camera overhead() {
    Camera c = test::lookAt({0.0, 3.0, 0.6}, {0.0, 0.0, 0.0});
    return c;
}

} // namespace

TEST(RendererChanges, UpdatesDrawWhatTheDecalsTakenWholeDrawWithCratersAndSplats) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        std::optional<Pair> p = makePair();
        ASSERT_TRUE(p);
        Rng rng(seed);
        std::deque<DecalHandle> handles;
        size_t volumetricSeen = 0, splattedSeen = 0;
        for (int frame = 0; frame < 12; ++frame) {
            play(*p, rng, handles);
            const DecalChanges c = p->sys->changesSince(p->version);
            ASSERT_TRUE(c.complete);
            p->version = c.version;
            const DecalSystem& sys = *p->sys;
            const CraterClipsOf clips = [&sys](size_t i) { return sys.craterClips(i); };
            p->changes->updateDecals(sys.decals(), c, clips);
            p->whole->setDecals(sys.decals(), clips);
            FrameStats a, b;
            const Image ia = test::renderView(*p->changes, overhead(), View::Final, &a);
            const Image ib = test::renderView(*p->whole, overhead(), View::Final, &b);
            ASSERT_EQ(imageDifference(ia, ib), "") << "seed " << seed << ", frame " << frame;
            EXPECT_EQ(a.decals, b.decals) << frame;
            EXPECT_EQ(a.decalsVolumetric, b.decalsVolumetric) << frame;
            EXPECT_EQ(a.decalsTextureSpace, b.decalsTextureSpace) << frame;
            EXPECT_EQ(a.decalsSplatted, b.decalsSplatted) << frame;
            EXPECT_EQ(a.decalsInvalid, b.decalsInvalid) << frame;
            EXPECT_EQ(a.decalsDrawn, b.decalsDrawn) << frame;
            EXPECT_EQ(a.decals + a.decalsVolumetric + a.decalsTextureSpace, p->sys->decals().size()) << frame;
            volumetricSeen += a.decalsVolumetric;
            splattedSeen += a.decalsSplatted;
        }
        EXPECT_GT(volumetricSeen, 0u);
        EXPECT_GT(splattedSeen, 0u);
        EXPECT_GT(p->sys->stats().evicted, 0u);
    }
}

TEST(RendererChanges, OneSpawnAmongCratersAndSplatsUploadsOneRecord) {
    std::optional<Pair> p = makePair();
    ASSERT_TRUE(p);
    Rng rng(6);
    std::deque<DecalHandle> handles;
    for (int frame = 0; frame < 3; ++frame)
        play(*p, rng, handles);
    p->changes->setDecals(p->sys->decals());
    p->version = p->sys->version();
    FrameStats st;
    test::renderView(*p->changes, overhead(), View::Final, &st);
    ASSERT_TRUE(p->sys->spawnAttached(0, glm::vec3(-0.5f, 0.2f, 0.0f), glm::vec3(0, 1, 0), 0).placed());
    const DecalChanges c = p->sys->changesSince(p->version);
    ASSERT_EQ(c.changes.size(), 1u);
    p->changes->updateDecals(p->sys->decals(), c);
    test::renderView(*p->changes, overhead(), View::Final, &st);
    // The new record (44 bytes), its draw-order entry and the visible list: no record of the others.
    EXPECT_LT(st.decalBytesUploaded, 44u + 4u + 4u * (st.decalsDrawn + 1));
    EXPECT_GT(st.decalBytesUploaded, 0u);
}
