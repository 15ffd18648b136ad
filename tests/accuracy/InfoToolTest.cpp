// spatter-info on builtin:gallery: one JSON object describing every object, and what the collision
// world shares between the objects placed with one mesh.

#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sys/wait.h>

using namespace spatter;
using spatter::test::kInfoTool;

TEST(SpatterInfo, DescribesEveryObjectAndTheCollisionMeshItUses) {
    if (!kInfoTool) GTEST_SKIP() << "spatter-info is not built";
    const std::string dir = test::scratchDir("info-gallery");
    const std::string command =
        std::string("'") + kInfoTool + "' builtin:gallery > '" + dir + "/out.json' 2> '" + dir + "/err.txt'";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << test::readFile(dir + "/err.txt");
    const nlohmann::json info = nlohmann::json::parse(test::readFile(dir + "/out.json"));
    const Result<Scene> scene = loadScene("builtin:gallery");
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(info["objects"], scene->objects.size());
    EXPECT_EQ(info["meshes"], scene->objects.size() - 3); // the targets keep one mesh, the banners one
    const nlohmann::json& detail = info["objects_detail"];
    ASSERT_EQ(detail.size(), scene->objects.size());
    size_t shared = 0;
    for (size_t i = 0; i < detail.size(); ++i) {
        const SceneObject& o = scene->objects[i];
        const nlohmann::json& d = detail[i];
        EXPECT_EQ(d["name"], o.name);
        EXPECT_EQ(d["instanced"], o.dynamic && o.receivesDecals) << o.name; // no static mesh four times
        const size_t of = d["collision_mesh_of"];
        ASSERT_LE(of, i) << o.name;
        if (of == i) continue;
        ++shared;
        EXPECT_EQ(scene->objects[of].mesh->positions, o.mesh->positions) << o.name;
        EXPECT_EQ(scene->objects[of].mesh->indices, o.mesh->indices) << o.name;
    }
    EXPECT_EQ(shared, 3u); // the second and third targets, the second banner
}

TEST(InfoTool, ExitsTwoOnAnUnknownOptionAsItsHelpSays) {
    if (!kInfoTool) GTEST_SKIP() << "spatter-info is not built";
    const std::string dir = test::scratchDir("info-usage");
    auto exitCode = [&](const std::string& args) {
        const std::string command =
            std::string("'") + kInfoTool + "' " + args + " > /dev/null 2> '" + dir + "/err.txt'";
        const int status = std::system(command.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    EXPECT_EQ(exitCode("--bogus"), 2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("unknown option --bogus"), std::string::npos);
    EXPECT_EQ(exitCode("-x"), 2);
    EXPECT_EQ(exitCode(""), 2);
    EXPECT_EQ(exitCode("builtin:gallery builtin:gallery"), 2);
    EXPECT_EQ(exitCode("'" + dir + "/missing.obj'"), 1);
    EXPECT_EQ(exitCode("--help"), 0);
}
