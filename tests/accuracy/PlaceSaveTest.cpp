// spatter-place --save: the state the tool saves is the state of a decal system that places the same
// rays here, byte for byte, and loads back into a system of the same scene.

#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/placement/RayParser.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

using namespace spatter;

namespace {

// The tool's decal system: no limits, one type of the size and angle it was given.
DecalSystem toolSystem(const Scene& scene, uint64_t seed, float size) {
    DecalSettings settings;
    settings.seed = seed;
    settings.maxPerCell = settings.budget = settings.maxPerObject = std::numeric_limits<uint32_t>::max();
    Result<DecalSystem> s = DecalSystem::create(scene, settings);
    EXPECT_TRUE(s.ok()) << s.error();
    DecalType type;
    type.name = "spatter-place";
    type.size = glm::vec2(size);
    EXPECT_TRUE(s->registerType(type).ok());
    return std::move(s).value();
}

TEST(SpatterPlaceSave, SavesWhatTheLibraryPlacesAndLoadsBack) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built (SPATTER_BUILD_APPS=OFF)";
    const std::string dir = test::scratchDir("accuracy-place-save");
    const std::string scenePath = dir + "/box.obj", save = dir + "/decals.save";
    ASSERT_TRUE(writeObj(makeBox(glm::vec3(1.0f), 4), scenePath));
    {
        std::ofstream out(dir + "/rays.txt");
        for (int i = 0; i < 40; ++i)
            out << 0.05 * (i % 9) - 0.2 << ' ' << 0.04 * (i % 7) - 0.1 << " 5 " << 0.01 * (i % 5) << ' '
                << -0.02 * (i % 3) << " -1\n";
    }
    const test::PlaceToolRun run =
        test::runPlaceTool("'" + scenePath + "' --rays '" + dir + "/rays.txt' --seed 9 --size 0.2 --save '" +
                               save + "' --summary",
                           dir);
    ASSERT_EQ(run.status, 0) << run.records;
    ASSERT_EQ(run.summary["placed"], 40);

    // The same rays placed here, as the tool reads them.
    std::ifstream in(dir + "/rays.txt");
    std::vector<Ray> rays;
    for (std::string line; std::getline(in, line);)
        rays.push_back(parseRayLine(line, 0).ray);
    Result<Scene> scene = loadScene(scenePath);
    ASSERT_TRUE(scene.ok()) << scene.error();
    DecalSystem here = toolSystem(scene.value(), 9, 0.2f);
    std::vector<SpawnResult> results;
    here.spawnBatch(rays, 0, results);
    std::ifstream file(save, std::ios::binary);
    const std::vector<uint8_t> saved((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    EXPECT_TRUE(saved == saveDecals(here)) << "the tool's save differs from the library's state";

    DecalSystem loaded = toolSystem(scene.value(), 1, 0.2f);
    Result<DecalLoadReport> r = loadDecalsFromFile(loaded, save);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_EQ(r->decals, 40u);
    EXPECT_EQ(r->droppedDecals, 0u);
    EXPECT_TRUE(saveDecals(loaded) == saved);
}

} // namespace
