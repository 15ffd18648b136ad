// spatter-place --time T: the scene traced as it stands at T of its first animation, and the records
// of decals on skinned objects carry the time and the render triangle they lie on.

#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

using namespace spatter;

namespace {

// Placed records of spatter-place's output.
std::vector<nlohmann::json> placed(const std::string& records) {
    std::vector<nlohmann::json> out;
    std::istringstream in(records);
    for (std::string line; std::getline(in, line);) {
        nlohmann::json r = nlohmann::json::parse(line, nullptr, false);
        if (r.is_object() && r["status"] == "placed") out.push_back(r);
    }
    return out;
}

} // namespace

TEST(SpatterPlaceTime, TracesThePoseAtTheTimeAndAnchorsDecalsOnTheSkin) {
    if (!test::kPlaceTool) GTEST_SKIP() << "the tools are not built";
    SPATTER_REQUIRE_SHARED(man, "gltf/CesiumMan/CesiumMan.glb");
    const std::string dir = test::scratchDir("place-time");
    std::ofstream rays(dir + "/rays.txt");
    for (int i = 0; i < 40; ++i) // a column of shots from the front at the walking figure's legs
        rays << (-0.3 + 0.015 * i) << " " << (0.15 + 0.01 * i) << " 3 0 0 -1\n";
    rays.close();
    const std::string args = "'" + man + "' --rays '" + dir + "/rays.txt' --size 0.05 --time ";
    const test::PlaceToolRun early = test::runPlaceTool(args + "0.3", dir);
    const test::PlaceToolRun late = test::runPlaceTool(args + "1.2", dir);
    ASSERT_EQ(WEXITSTATUS(early.status), 0) << early.records;
    ASSERT_EQ(WEXITSTATUS(late.status), 0) << late.records;
    const std::vector<nlohmann::json> a = placed(early.records), b = placed(late.records);
    ASSERT_GT(a.size(), 5u);
    ASSERT_GT(b.size(), 5u);
    EXPECT_NE(early.records, late.records) << "the legs walk between the two times";
    for (const nlohmann::json& r : a) {
        EXPECT_EQ(r["time"], 0.3);
        ASSERT_TRUE(r.contains("anchor")) << r.dump();
        EXPECT_LT(r["anchor"]["triangle"].get<uint32_t>(), 4672u);
        const nlohmann::json& bary = r["anchor"]["bary"];
        EXPECT_NEAR(bary[0].get<double>() + bary[1].get<double>() + bary[2].get<double>(), 1.0, 1e-9);
    }

    const test::PlaceToolRun bad = test::runPlaceTool(args + "soon", dir);
    EXPECT_EQ(WEXITSTATUS(bad.status), 2);
    EXPECT_NE(test::readFile(dir + "/stderr.txt").find("--time"), std::string::npos);
}
