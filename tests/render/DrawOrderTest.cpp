// Draw order (DecalType::priority): overlapping decals draw in priority order whatever their spawn
// order, and within a priority newer over older, in every host path (G-buffer blend and forward with
// culling on the CPU and on the GPU, DBuffer).

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/render/DecalProjector.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <string>

using namespace spatter;

namespace {

enum class Path { Blend, BlendGpuCulled, DBuffer, Forward, ForwardGpuCulled };

const char* name(Path p) {
    switch (p) {
    case Path::Blend:
        return "G-buffer blend";
    case Path::BlendGpuCulled:
        return "G-buffer blend, GPU culling";
    case Path::DBuffer:
        return "DBuffer";
    case Path::Forward:
        return "forward";
    case Path::ForwardGpuCulled:
        break;
    }
    return "forward, GPU culling";
}

// An opaque square decal type of one colour.
DecalType solid(int layer, const glm::vec3& colour, int priority) {
    DecalType t;
    t.name = "solid";
    t.texture = layer;
    t.tint = glm::vec4(colour, 1.0f);
    t.priority = priority;
    t.normalMap = false;
    t.depthFade = DepthFade::None;
    return t;
}

struct Counts {
    size_t red = 0, blue = 0;
};

// Two decals on the same spot of the wall, red (type 0) spawned at `redTime` and blue (type 1) at
// `blueTime`, given to the projector blue first when `blueFirst`; the red and blue pixels the path
// leaves in the albedo.
Counts drawPair(Path path, int redPriority, int bluePriority, double redTime, double blueTime,
                bool blueFirst) {
    std::optional<test::HostedWall> h = test::HostedWall::make();
    if (!h) return {};
    if (path == Path::BlendGpuCulled || path == Path::ForwardGpuCulled) {
        ProjectorSettings settings;
        settings.gpuCullingFrom = 0;
        Result<DecalProjector> p = DecalProjector::create(settings);
        EXPECT_TRUE(p.ok()) << p.error();
        if (!p) return {};
        h->projector = std::move(p).value();
        EXPECT_TRUE(h->projector.setObjects(h->wall.transforms, h->wall.ids).ok());
    }
    Image white;
    white.width = white.height = 16;
    white.rgba.assign(16 * 16 * 4, 255);
    Result<int> layer = h->projector.addDecalTexture(white);
    EXPECT_TRUE(layer.ok()) << layer.error();
    if (!layer) return {};
    h->projector.setDecalTypes(
        {solid(layer.value(), {1, 0, 0}, redPriority), solid(layer.value(), {0, 0, 1}, bluePriority)});
    Decal red = test::WallScene::decalAt(0, {-0.6f, 0.0f, 0.05f}), blue = red;
    red.type = 0;
    red.spawnTime = redTime;
    blue.type = 1;
    blue.spawnTime = blueTime;
    h->projector.setDecals(blueFirst ? std::vector<Decal>{blue, red} : std::vector<Decal>{red, blue});

    const HostFrame f = h->host.frame(h->wall.camera, true);
    uint32_t albedo = f.albedoTexture;
    if (path == Path::Forward || path == Path::ForwardGpuCulled) {
        Result<ProjectorStats> st =
            h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector);
        EXPECT_TRUE(st.ok()) << st.error();
    } else {
        ProjectorDraw options;
        if (path == Path::DBuffer) options.path = ProjectorPath::DBuffer;
        Result<ProjectorStats> st = h->projector.draw(f, options);
        EXPECT_TRUE(st.ok()) << st.error();
        if (st) {
            EXPECT_EQ(st->gpuCulled, path == Path::BlendGpuCulled);
        }
        if (path == Path::DBuffer) albedo = h->projector.resources().dbufferAlbedo; // opaque: the top decal
    }
    const Image image = h->host.read(albedo);
    Counts c;
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        const int r = image.rgba[i], b = image.rgba[i + 2];
        c.red += r > 200 && b < 50 ? 1 : 0;
        c.blue += b > 200 && r < 50 ? 1 : 0;
    }
    return c;
}

constexpr Path kPaths[] = {Path::Blend, Path::BlendGpuCulled, Path::DBuffer, Path::Forward,
                           Path::ForwardGpuCulled};

} // namespace

TEST(DrawOrder, AHigherPriorityDrawsOverALowerOneWhateverTheSpawnOrder) {
    SPATTER_REQUIRE_GL(gl);
    for (const Path p : kPaths)
        for (const bool blueFirst : {false, true}) {
            // The blue decal is newer but of a lower priority: red stays on top.
            const Counts c = drawPair(p, 1, 0, 0.0, 1.0, blueFirst);
            std::printf("%s, blue given %s: %zu red, %zu blue pixels\n", name(p),
                        blueFirst ? "first" : "second", c.red, c.blue);
            EXPECT_GT(c.red, 40u) << name(p);
            EXPECT_EQ(c.blue, 0u) << name(p);
        }
}

TEST(DrawOrder, WithinAPriorityNewerDrawsOverOlder) {
    SPATTER_REQUIRE_GL(gl);
    for (const Path p : kPaths)
        for (const bool blueFirst : {false, true}) {
            const Counts c = drawPair(p, 0, 0, 0.0, 1.0, blueFirst); // blue is newer
            EXPECT_GT(c.blue, 40u) << name(p);
            EXPECT_EQ(c.red, 0u) << name(p);
            const Counts d = drawPair(p, 0, 0, 2.0, 1.0, blueFirst); // red is newer
            EXPECT_GT(d.red, 40u) << name(p);
            EXPECT_EQ(d.blue, 0u) << name(p);
        }
}
