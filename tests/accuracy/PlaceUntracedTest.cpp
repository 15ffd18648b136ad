// spatter-place on a glTF scene whose dynamic node has a transform single precision cannot trace:
// the scene loads, the node is left out with a warning on stderr, and the rest traces as usual.

#include "GltfBuilder.hpp"
#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sys/wait.h>

using namespace spatter;
using ::testing::HasSubstr;

TEST(SpatterPlaceUntraced, ANodeSingularInFloatIsLeftOutWithAWarningAndTheFloorStillTraces) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const std::string dir = test::scratchDir("place-untraced");
    const Mesh box = makeBox(glm::vec3(0.5f), 1);
    test::GltfBuilder g = test::floorAndCrate(box.positions, box.indices, test::kColumnsEqualInFloat, true);
    const std::string scene = g.writeGltf(dir, "crate");
    std::ofstream(dir + "/rays.txt") << "0 10 0 0 -1 0\n0.05 10 0 0.01 -1 0\n";

    const test::PlaceToolRun run = test::runPlaceTool("'" + scene + "' --rays '" + dir + "/rays.txt'", dir);
    ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << test::readFile(dir + "/stderr.txt");
    EXPECT_THAT(
        test::readFile(dir + "/stderr.txt"),
        HasSubstr("spatter-place: warning: object 1 (crate): transform is singular in single precision"));
    std::istringstream records(run.records);
    std::string line;
    int placed = 0;
    while (std::getline(records, line)) {
        const nlohmann::json r = nlohmann::json::parse(line);
        EXPECT_EQ(r["status"], "placed") << line;
        EXPECT_EQ(r["object"], "floor") << line;
        ++placed;
    }
    EXPECT_EQ(placed, 2);
}
