// spatter-place --proxy TOL% [--cache DIR]: the same proxies as buildProxy with a tolerance relative
// to each object's diagonal, one build for the objects that share a mesh, and a cache that makes a
// second run build nothing.

#include "GltfBuilder.hpp"
#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>

using namespace spatter;

namespace {

// Writes a bumpy sphere (9,120 triangles, above the own-mesh threshold) as OBJ.
Status writeBumpySphere(const std::string& path) {
    Mesh m = makeSphere(2.0f, 48, 96);
    displace(m, [](const glm::vec3& p, const glm::vec3&) {
        return 0.06f * std::sin(4.5f * p.x) * std::cos(3.5f * p.y);
    });
    return writeObj(m, path);
}

test::PlaceToolRun place(const std::string& dir, const std::string& scene, const std::string& extra) {
    return test::runPlaceTool("'" + scene + "' --rays '" + dir + "/rays.txt' --proxy 1% --summary " + extra,
                              dir);
}

TEST(SpatterPlaceProxy, UsesTheBuildersBoundAndTheCacheMakesTheSecondRunBuildNothing) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built (SPATTER_BUILD_APPS=OFF)";
    const std::string dir = test::scratchDir("accuracy-place-tool");
    const std::string scene = dir + "/sphere.obj", cache = dir + "/cache";
    ASSERT_TRUE(writeBumpySphere(scene));
    {
        std::ofstream rays(dir + "/rays.txt");
        rays << "0 0 10 0 0 -1\n5 1 0 -1 0 0\n0.3 -8 0.2 0 1 0\n";
    }

    // The proxy spatter-place builds is buildProxy's with a tolerance of 1% of the diagonal.
    Result<Scene> loaded = loadScene(scene);
    ASSERT_TRUE(loaded) << loaded.error();
    ProxySettings settings;
    settings.tolerance = 0.01f;
    settings.toleranceRelative = true;
    Result<Proxy> proxy = buildProxy(*loaded->objects.at(0).mesh, settings);
    ASSERT_TRUE(proxy) << proxy.error();
    ASSERT_EQ(proxy->source, ProxySource::Simplified);

    const test::PlaceToolRun first = place(dir, scene, "--cache '" + cache + "'");
    ASSERT_EQ(first.status, 0) << first.records;
    ASSERT_TRUE(first.summary.is_object());
    EXPECT_EQ(first.summary["proxies_built"], 1);
    EXPECT_EQ(first.summary["proxies_cached"], 0);
    EXPECT_EQ(first.summary["proxy_triangles"].get<size_t>(), proxy->proxyTriangles);
    size_t placed = 0;
    std::istringstream lines(first.records);
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json rec = nlohmann::json::parse(line, nullptr, false);
        ASSERT_TRUE(rec.is_object()) << line;
        if (rec["status"] != "placed") continue;
        placed++;
        EXPECT_EQ(rec["proxy_error_bound"].get<double>(), proxy->errorBound);
        EXPECT_GE(rec["half_depth"].get<double>(), proxy->errorBound);
    }
    EXPECT_EQ(placed, 3u);

    const test::PlaceToolRun second = place(dir, scene, "--cache '" + cache + "'");
    ASSERT_EQ(second.status, 0);
    EXPECT_EQ(second.summary["proxies_built"], 0);
    EXPECT_EQ(second.summary["proxies_cached"], 1);
    EXPECT_EQ(second.records, first.records);

    // A corrupt entry is rebuilt, with the same result.
    size_t entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(cache)) {
        std::ofstream(e.path(), std::ios::binary | std::ios::trunc) << "corrupt";
        entries++;
    }
    ASSERT_EQ(entries, 1u);
    const test::PlaceToolRun third = place(dir, scene, "--cache '" + cache + "'");
    ASSERT_EQ(third.status, 0);
    EXPECT_EQ(third.summary["proxies_built"], 1);
    EXPECT_EQ(third.records, first.records);

    // Without --cache nothing is cached; --cache needs a proxy mode that builds proxies.
    const test::PlaceToolRun uncached = place(dir, scene, "");
    EXPECT_EQ(uncached.summary["proxies_built"], 1);
    EXPECT_EQ(uncached.records, first.records);
    const std::string bad = std::string("'") + test::kPlaceTool + "' '" + scene + "' --cache '" + cache +
                            "' < /dev/null > /dev/null 2>&1";
    const int status = std::system(bad.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
}

// Two nodes of one mesh (one static, one dynamic) and a node of another: two builds, and the second
// node takes the first one's proxy, bound and all.
TEST(SpatterPlaceProxy, ObjectsThatShareAMeshShareOneBuild) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built (SPATTER_BUILD_APPS=OFF)";
    const std::string dir = test::scratchDir("accuracy-place-shared");
    test::GltfBuilder g;
    for (float bumps : {4.5f, 6.5f}) {
        Mesh m = makeSphere(2.0f, 24, 48);
        displace(m, [bumps](const glm::vec3& p, const glm::vec3&) { return 0.06f * std::sin(bumps * p.x); });
        g.addMesh(m.positions, m.indices);
    }
    g.push("nodes", {{"name", "a"}, {"mesh", 0}});
    g.push("nodes",
           {{"name", "b"}, {"mesh", 0}, {"translation", {10, 0, 0}}, {"extras", {{"dynamic", true}}}});
    g.push("nodes", {{"name", "c"}, {"mesh", 1}, {"translation", {-10, 0, 0}}});
    g.doc["scenes"] = {{{"nodes", {0, 1, 2}}}};
    g.doc["scene"] = 0;
    const std::string scene = g.writeGltf(dir, "shared");
    std::ofstream(dir + "/rays.txt") << "0.1 0.2 10 0 0 -1\n10.1 0.2 10 0 0 -1\n-9.9 0.2 10 0 0 -1\n";

    const test::PlaceToolRun run = place(dir, scene, "");
    ASSERT_EQ(run.status, 0) << run.records;
    EXPECT_EQ(run.summary["proxies_built"], 2);
    EXPECT_EQ(run.summary["proxies_shared"], 1);
    std::map<std::string, double> bounds;
    std::istringstream lines(run.records);
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json rec = nlohmann::json::parse(line, nullptr, false);
        ASSERT_TRUE(rec.is_object()) << line;
        ASSERT_EQ(rec["status"], "placed") << line;
        bounds[rec["object"].get<std::string>()] = rec["proxy_error_bound"].get<double>();
    }
    ASSERT_EQ(bounds.size(), 3u);
    EXPECT_GT(bounds["a"], 0.0);
    EXPECT_EQ(bounds["b"], bounds["a"]);
    EXPECT_NE(bounds["c"], bounds["a"]);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
}

} // namespace

TEST(SpatterPlaceSize, DecalsWithoutASizeTakeTwoPercentOfTheScenesDiagonal) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built (SPATTER_BUILD_APPS=OFF)";
    const std::string dir = test::scratchDir("accuracy-place-size");
    const std::string scene = dir + "/sphere.obj";
    ASSERT_TRUE(writeBumpySphere(scene));
    {
        std::ofstream rays(dir + "/rays.txt");
        rays << "0 0 10 0 0 -1\n";
    }
    Result<Scene> loaded = loadScene(scene);
    ASSERT_TRUE(loaded) << loaded.error();
    const double expected = 0.02 * glm::length(loaded->worldBounds().extent());
    for (const auto& [extra, size] : {std::pair<std::string, double>{"", expected}, {"--size 0.25", 0.25}}) {
        const test::PlaceToolRun run =
            test::runPlaceTool("'" + scene + "' --rays '" + dir + "/rays.txt' " + extra, dir);
        ASSERT_EQ(run.status, 0) << run.records;
        const nlohmann::json rec =
            nlohmann::json::parse(run.records.substr(0, run.records.find('\n')), nullptr, false);
        ASSERT_TRUE(rec.is_object() && rec["status"] == "placed") << run.records;
        EXPECT_NEAR(rec["size"][0].get<double>(), size, 1e-6 * size) << extra;
        EXPECT_NEAR(rec["size"][1].get<double>(), size, 1e-6 * size) << extra;
    }
}
