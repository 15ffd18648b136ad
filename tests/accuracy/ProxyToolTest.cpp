// spatter-proxy: a certified proxy of a mesh file, written as OBJ with its report, the same whatever
// the number of threads the build is given; bad usage exits 2 (options given twice or without their
// values, numbers that are not decimal, outputs that are inputs or cannot be written), a mesh it
// cannot read 1; a failed run leaves no output.

#include "PlaceToolRun.hpp"
#include "ReferenceGeometry.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
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

namespace {

// A wall of two triangles as OBJ in `dir` (its own proxy at any tolerance).
std::string writeProxyWall(const std::string& dir) {
    const std::string path = dir + "/wall.obj";
    std::ofstream(path) << "v -4 0 0\nv 4 0 0\nv 4 4 0\nv -4 4 0\nf 1 2 3\nf 1 3 4\n";
    return path;
}

} // namespace

TEST(ProxyTool, RefusesAnOutputThatIsItsMeshOrTheOtherOutput) {
    if (!kProxyTool) GTEST_SKIP() << "spatter-proxy is not built";
    const std::string dir = test::scratchDir("proxy-same-file");
    const std::string wall = writeProxyWall(dir), mesh = test::readFile(wall);
    EXPECT_EQ(runProxyTool("'" + wall + "' --tolerance 1% --out '" + dir + "/./wall.obj'", dir), 2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("MESH and --out name the same file"), std::string::npos);
    EXPECT_EQ(test::readFile(wall), mesh);
    EXPECT_EQ(
        runProxyTool("'" + wall + "' --tolerance 1% --out '" + dir + "/p.obj' --report '" + dir + "/p.obj'",
                     dir),
        2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("--out and --report name the same file"),
              std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.obj"));
}

TEST(ProxyTool, LeavesNoOutputWhenTheReportCannotBeWritten) {
    if (!kProxyTool) GTEST_SKIP() << "spatter-proxy is not built";
    const std::string dir = test::scratchDir("proxy-report-fails");
    const std::string wall = "'" + writeProxyWall(dir) + "' --tolerance 1% --quiet --out '" + dir + "/p.obj'";
    EXPECT_EQ(runProxyTool(wall + " --report '" + dir + "/no/such/folder/r.json'", dir), 2); // checked first
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.obj"));
    EXPECT_EQ(runProxyTool(wall + " --report '" + dir + "'", dir), 2); // a directory
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.obj"));
    if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full to fail a write";
    EXPECT_EQ(runProxyTool(wall + " --report /dev/full", dir), 1); // fails as it is written
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.obj"));
}

TEST(ProxyTool, RefusesAMissingValueARepeatedOptionAndNumbersThatAreNotDecimal) {
    if (!kProxyTool) GTEST_SKIP() << "spatter-proxy is not built";
    const std::string dir = test::scratchDir("proxy-usage");
    const std::string wall = "'" + writeProxyWall(dir) + "'", out = " --out '" + dir + "/p.obj'";
    EXPECT_EQ(runProxyTool(wall + " --tolerance 1% --out --quiet", dir), 2);
    EXPECT_EQ(runProxyTool(wall + " --tolerance 1%" + out + " --report --quiet", dir), 2);
    EXPECT_FALSE(std::filesystem::exists(dir + "/--quiet"));
    EXPECT_EQ(runProxyTool(wall + " --tolerance 1% --tolerance 2%" + out, dir), 2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("--tolerance given twice"), std::string::npos);
    EXPECT_EQ(runProxyTool(wall + " --tolerance 1% --quiet --quiet" + out, dir), 2);
    for (const char* bad : {"--tolerance 0x10", "--tolerance 1e300", "--tolerance ''", "--tolerance ' 1'",
                            "--tolerance 1% --max-triangles 0x10", "--tolerance 1% --threads 1e1",
                            "--tolerance 1% --threads ' 4'", "--tolerance 1% --threads +4"})
        EXPECT_EQ(runProxyTool(wall + " " + bad + out, dir), 2) << bad;
    EXPECT_EQ(runProxyTool(wall + " --tolerance ''" + out, dir), 2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("not ''"), std::string::npos)
        << test::readFile(dir + "/err.txt");
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.obj"));
    EXPECT_EQ(runProxyTool(wall + " --tolerance 1e-3 --max-triangles 10 --threads 4 --quiet" + out, dir), 0)
        << test::readFile(dir + "/err.txt");
}

TEST(ProxyTool, RefusesACacheThatIsAFile) {
    if (!kProxyTool) GTEST_SKIP() << "spatter-proxy is not built";
    const std::string dir = test::scratchDir("proxy-cache-file");
    const std::string wall = writeProxyWall(dir);
    EXPECT_EQ(
        runProxyTool("'" + wall + "' --tolerance 1% --out '" + dir + "/p.obj' --cache '" + wall + "'", dir),
        2);
    EXPECT_NE(test::readFile(dir + "/err.txt").find("is not a directory"), std::string::npos);
}
