// spatter-proxy: a certified proxy of a mesh file, written as OBJ with its report, the same whatever
// the number of threads the build is given; bad usage exits 2, a mesh it cannot read 1.

#include "PlaceToolRun.hpp"
#include "ReferenceGeometry.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <sys/wait.h>

using namespace spatter;
using spatter::test::galleryMesh;
using spatter::test::kProxyTool;

namespace {

// The gallery's second pillar as OBJ in `dir` (positions to the float bit), and its triangles.
std::string writePillar(const std::string& dir, size_t& triangles) {
    const std::shared_ptr<const Mesh> pillar = galleryMesh("pillar_2");
    triangles = pillar->triangleCount();
    const std::string path = dir + "/pillar.obj";
    EXPECT_TRUE(writeObj(*pillar, path).ok()) << path;
    return path;
}

// The exit code of `spatter-proxy build ARGS` (-1 when it did not exit).
int runProxyTool(const std::string& args, const std::string& dir) {
    const std::string command =
        std::string("'") + kProxyTool + "' build " + args + " 2> '" + dir + "/err.txt'";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST(SpatterProxy, WritesACertifiedProxyThatTheThreadCountDoesNotChange) {
    if (!kProxyTool) GTEST_SKIP() << "spatter-proxy is not built";
    const std::string dir = test::scratchDir("proxy-tool");
    size_t triangles = 0;
    const std::string pillar = writePillar(dir, triangles);
    for (const char* threads : {"0", "1", "8", "16"})
        ASSERT_EQ(runProxyTool(pillar + " --tolerance 1% --quiet --threads " + threads + " --out '" + dir +
                                   "/p" + threads + ".obj' --report '" + dir + "/p" + threads + ".json'",
                               dir),
                  0)
            << test::readFile(dir + "/err.txt");
    const nlohmann::json report = nlohmann::json::parse(test::readFile(dir + "/p0.json"));
    EXPECT_EQ(report["input_triangles"], triangles);
    EXPECT_LT(report["proxy_triangles"], report["input_triangles"].get<size_t>() / 4);
    EXPECT_LE(report["error_bound"].get<double>(), report["tolerance"].get<double>());
    EXPECT_EQ(report["backend"], "meshopt");
    for (const char* threads : {"1", "8", "16"}) {
        EXPECT_EQ(test::readFile(dir + "/p" + threads + ".obj"), test::readFile(dir + "/p0.obj")) << threads;
        const nlohmann::json other = nlohmann::json::parse(test::readFile(dir + "/p" + threads + ".json"));
        EXPECT_EQ(other["error_bound"], report["error_bound"]) << threads;
        EXPECT_EQ(other["proxy_triangles"], report["proxy_triangles"]) << threads;
    }
    const std::string out = " --out '" + dir + "/x.obj'";
    EXPECT_EQ(runProxyTool(pillar + " --tolerance 1%" + out + " --threads 17", dir), 2);
    EXPECT_EQ(runProxyTool(pillar + " --tolerance 1%" + out + " --threads 1.5", dir), 2);
    EXPECT_EQ(runProxyTool(pillar + out, dir), 2); // no tolerance
    EXPECT_EQ(runProxyTool("'" + dir + "/missing.obj' --tolerance 1%" + out, dir), 1);
}
