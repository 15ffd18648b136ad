#include "TestData.hpp"
#include "ToolGl.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <string>
#include <sys/wait.h>

using namespace spatter;

namespace {

// Runs spatter-bench with `args`, its output into `log`; returns the exit code (-1 when it did not
// exit normally).
int runBench(const std::string& args, const std::string& log) {
    const std::string cmd = std::string(SPATTER_BENCH_TOOL) + " " + args + " >" + log + " 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json readJson(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, false);
}

// A sphere of 2,048 triangles as an OBJ file.
std::string writeSphere(const std::string& dir) {
    const Mesh m = makeSphere(1.0f, 17, 64);
    const std::string path = dir + "/sphere.obj";
    std::ofstream f(path);
    for (const glm::vec3& p : m.positions)
        f << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        f << "f " << m.indices[t] + 1 << " " << m.indices[t + 1] + 1 << " " << m.indices[t + 2] + 1 << "\n";
    return path;
}

// Runs spatter-bench tradeoff with `options` on a sphere written to a scratch folder named `name`;
// its JSON, or null when it failed (the log is then reported).
nlohmann::json tradeoffOnSphere(const std::string& name, const std::string& options) {
    const std::string dir = test::scratchDir(name);
    const int code =
        runBench("tradeoff " + writeSphere(dir) + " " + options + " --json " + dir + "/t.json", dir + "/log");
    EXPECT_EQ(code, 0) << readAll(dir + "/log");
    return code == 0 ? readJson(dir + "/t.json") : nlohmann::json();
}

} // namespace

TEST(BenchSmoke, PlacementQuickWritesTheContractKeys) {
    const std::string dir = test::scratchDir("bench-placement");
    ASSERT_EQ(runBench("placement --quick --json " + dir + "/p.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/p.json");
    ASSERT_TRUE(j.is_object()) << readAll(dir + "/p.json");
    for (const char* key : {"raw_single_ns", "raw_packet_ns", "spawn_ns", "spawn_batch_ns", "spawn_over_raw",
                            "batch_speedup"}) {
        ASSERT_TRUE(j.contains(key) && j[key].is_number()) << key;
        EXPECT_GT(j[key].get<double>(), 0.0) << key;
    }
    // Every ray of both sets was spawned: the statuses add up to the rays.
    for (const char* set : {"scattered", "shotgun"}) {
        size_t total = 0;
        for (const auto& [status, count] : j["sets"][set]["spawn_statuses"].items())
            total += count.get<size_t>();
        EXPECT_EQ(total, j["sets"][set]["rays"].get<size_t>()) << set;
    }
}

TEST(BenchSmoke, TradeoffWritesOneRowPerBackendAndTolerance) {
    const nlohmann::json j =
        tradeoffOnSphere("bench-tradeoff", "--subdivide 1 --backends meshopt --tolerances 1,5 --rays 300 "
                                           "--passes 1 --no-render --no-peer");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << j.dump();
    ASSERT_EQ(j["rows"].size(), 3u); // the render mesh, then meshopt at 1% and 5%
    EXPECT_EQ(j["rows"][0]["backend"], "render");
    EXPECT_EQ(j["rows"][0]["proxy_triangles"], 4 * 2048); // one Loop step
    for (const auto& row : j["rows"])
        for (const char* key : {"backend", "tolerance_rel", "proxy_triangles", "build_s", "placement_ns",
                                "batch_ns", "dist_p50_rel", "dist_p99_rel", "dist_max_rel", "normal_deg_p99",
                                "disagree_rate", "coverage_iou"})
            EXPECT_TRUE(row.contains(key)) << key;
    const nlohmann::json& coarse = j["rows"][2];
    EXPECT_EQ(coarse["backend"], "meshopt");
    EXPECT_DOUBLE_EQ(coarse["tolerance_rel"].get<double>(), 0.05);
    EXPECT_LT(coarse["proxy_triangles"].get<int>(), 2048);
    EXPECT_EQ(j["mesh"], "sphere-loop1");
    // Proxy hits lie within the certified bound of the render surface.
    EXPECT_LE(coarse["dist_max_rel"].get<double>(),
              coarse["error_bound_rel"].get<double>() * 1.000001 + 1e-9);
    EXPECT_TRUE(coarse["coverage_iou"].is_null()); // --no-render
}

TEST(BenchSmoke, TradeoffBreaksTheIouDownByTheFieldsTakenFromTheRenderPlacedDecal) {
    SPATTER_REQUIRE_TOOL_GL();
    const nlohmann::json j = tradeoffOnSphere(
        "bench-iou-breakdown", "--backends meshopt --tolerances 1 --rays 300 --passes 1 "
                               "--coverage-decals 40 --size 320x240 --no-peer --iou-breakdown");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << j.dump();
    ASSERT_EQ(j["rows"].size(), 2u) << j.dump();
    const nlohmann::json& proxy = j["rows"][1];
    ASSERT_TRUE(proxy.contains("iou_breakdown")) << proxy.dump();
    const nlohmann::json& b = proxy["iou_breakdown"];
    for (const char* key :
         {"centre", "frame", "frame_slant", "centre_frame_slant", "all", "centre_depth", "all_placed_by_both",
          "drawn_probe", "drawn_probe_seen", "drawn_probe_depth_normal", "nearest_face_frame"}) {
        EXPECT_GT(b[key].get<double>(), 0.0) << key;
        EXPECT_LE(b[key].get<double>(), 1.0) << key;
    }
    // Taking every field leaves only the shots one surface places and the other does not; dropping the
    // decals the render mesh does not place leaves those only it places.
    EXPECT_GE(b["all"].get<double>(), proxy["coverage_iou"].get<double>()) << proxy.dump();
    EXPECT_GT(b["all"].get<double>(), 0.9) << proxy.dump();
    EXPECT_GT(b["all_placed_by_both"].get<double>(), 0.9) << proxy.dump();
    // Re-laid on the drawn surface, the decals cover more of what the render-placed ones cover.
    EXPECT_GT(b["drawn_probe"].get<double>(), proxy["coverage_iou"].get<double>()) << proxy.dump();
}

TEST(BenchSmoke, ProxyComparesWithPlainMeshoptimizerInOneRun) {
    const std::string dir = test::scratchDir("bench-proxy");
    const std::string mesh = writeSphere(dir);
    ASSERT_EQ(runBench("proxy --meshes " + mesh + " --tolerances 1,5 --samples 2000 --no-gallery --json " +
                           dir + "/p.json",
                       dir + "/log"),
              0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/p.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/p.json");
    ASSERT_EQ(j["rows"].size(), 2u);
    for (const auto& row : j["rows"]) {
        for (const char* key : {"mesh", "tolerance_pct", "input_triangles", "anchor_triangles",
                                "anchor_target", "anchor_dense", "meshopt_s", "proxy_triangles", "proxy_h",
                                "proxy_dense", "proxy_met", "proxy_s", "triangles_ratio", "time_ratio"})
            EXPECT_TRUE(row.contains(key)) << key;
        EXPECT_EQ(row["input_triangles"], 2048);
        EXPECT_LT(row["proxy_triangles"].get<int>(), 2048);
        // The certified bound is never below the dense estimate, and the anchor is within the tolerance.
        EXPECT_GE(row["proxy_h"].get<double>(), row["proxy_dense"].get<double>());
        EXPECT_LE(row["anchor_dense"].get<double>(), row["tolerance"].get<double>());
    }
    ASSERT_EQ(j["tenth_percent"].size(), 1u);
    EXPECT_TRUE(j["gallery_cold"].is_null()); // --no-gallery
}

TEST(BenchSmoke, MemoryQuickReportsBytesPerDecal) {
    const std::string dir = test::scratchDir("bench-memory");
    ASSERT_EQ(runBench("memory --quick --no-gpu --json " + dir + "/m.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/m.json");
    ASSERT_TRUE(j.is_object()) << readAll(dir + "/m.json");
    // At least the Decal record itself per decal.
    EXPECT_GE(j["cpu_bytes_per_decal"].get<double>(), j["decal_record_bytes"].get<double>());
    EXPECT_GT(j["objects"]["proxy"]["bvh_user_bytes"].get<double>(), 0.0);
}

TEST(BenchSmoke, PersistenceQuickSavesAndLoadsEveryDecal) {
    const std::string dir = test::scratchDir("bench-persistence");
    ASSERT_EQ(runBench("persistence --quick --json " + dir + "/s.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/s.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/s.json");
    EXPECT_EQ(j["rows"].size(), 4u);
    EXPECT_GT(j["decals"].get<double>(), 0.0);
    // At most the Decal record per decal, plus the fixed part, shared by 20,000 decals.
    EXPECT_LE(j["bytes_per_decal"].get<double>(), j["decal_record_bytes"].get<double>());
    for (const auto& row : j["rows"])
        EXPECT_GT(row["mb_per_s"].get<double>(), 0.0) << row.dump();
}

TEST(BenchSmoke, PoseQuickTimesCesiumMansPosePerFrame) {
    SPATTER_REQUIRE_SHARED(scene, "gltf/CesiumMan/CesiumMan.glb");
    const std::string dir = test::scratchDir("bench-pose");
    ASSERT_EQ(runBench("pose --quick --json " + dir + "/p.json", dir + "/log"), 0) << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/p.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/p.json");
    EXPECT_EQ(j["joints"], 19);
    EXPECT_EQ(j["rows"].size(), 3u);
    for (const auto& row : j["rows"])
        EXPECT_GT(row["us_per_frame"].get<double>(), 0.0) << row.dump();
}

TEST(BenchSmoke, SkinnedQuickMeasuresEveryModelInOneRun) {
    SPATTER_REQUIRE_SHARED(cesium, "gltf/CesiumMan/CesiumMan.glb");
    SPATTER_REQUIRE_SHARED(rigged, "gltf/RiggedSimple/RiggedSimple.glb");
    const std::string dir = test::scratchDir("bench-skinned");
    ASSERT_EQ(runBench("skinned --quick --json " + dir + "/s.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/s.json");
    ASSERT_TRUE(j.is_object()) << readAll(dir + "/s.json");
    const size_t models = 4;
    ASSERT_EQ(j["models"].size(), models) << j.dump();
    // Per model: two collision meshes posed, one spawn comparison, three drift methods, two bounds,
    // coverage at four times of the cycle, three methods followed in the image.
    ASSERT_EQ(j["pose_update"].size(), 2 * models);
    ASSERT_EQ(j["spawn"].size(), models);
    ASSERT_EQ(j["drift"].size(), 3 * models);
    ASSERT_EQ(j["pose_bounds"].size(), 2 * models);
    ASSERT_EQ(j["accuracy"].size(), 4 * models);
    for (const auto& row : j["pose_update"]) {
        EXPECT_GT(row["triangles"].get<size_t>(), 0u) << row.dump();
        EXPECT_GT(row["ms_per_call"].get<double>(), 0.0) << row.dump();
    }
    for (const auto& row : j["spawn"]) {
        EXPECT_GT(row["placed_skinned"].get<size_t>(), 0u) << row.dump();
        EXPECT_GT(row["ratio"].get<double>(), 0.0) << row.dump();
        EXPECT_GT(row["proxy_ratio"].get<double>(), 0.0) << row.dump();
    }
    for (const auto& row : j["drift"]) {
        EXPECT_GT(row["samples"].get<size_t>(), 0u) << row.dump();
        EXPECT_GE(row["max"].get<double>(), row["median"].get<double>()) << row.dump();
    }
    for (const auto& row : j["pose_bounds"])
        EXPECT_GE(row["bound"].get<double>(), row["sampled_max"].get<double>()) << row.dump();
    // Without an OpenGL context the rows are there, not measured.
    const bool measured = j["coverage"] == "measured";
    EXPECT_EQ(measured, test::noToolGl().empty()) << j["coverage"].dump();
    for (const auto& row : j["accuracy"]) {
        ASSERT_EQ(row["iou"].is_number(), measured) << row.dump();
        if (!measured) continue;
        EXPECT_GT(row["placed_render"].get<size_t>(), 0u) << row.dump();
        EXPECT_GT(row["iou"].get<double>(), 0.0) << row.dump();
        EXPECT_LE(row["iou"].get<double>(), 1.0) << row.dump();
    }
    ASSERT_EQ(j["image_drift"].size(), measured ? 3 * models : 0u);
    for (const auto& row : j["image_drift"]) {
        // The splat needs a UV layout without overlaps: of these, CesiumMan's alone.
        if (row["method"] == "texture-space splat" && row["model"] != "gltf/CesiumMan/CesiumMan.glb") {
            EXPECT_TRUE(row["unavailable"].is_string()) << row.dump();
            continue;
        }
        EXPECT_GT(row["decals"].get<size_t>(), 0u) << row.dump();
        EXPECT_GT(row["samples"].get<size_t>(), 0u) << row.dump();
        if (row["method"] == "skin anchors, projected") {
            EXPECT_LT(row["max"].get<double>(), 0.05) << row.dump();
        }
        if (row["method"] == "texture-space splat") {
            EXPECT_GT(row["splat_ms"].get<double>(), 0.0) << row.dump();
        }
    }
}

TEST(BenchSmoke, RenderQuickTimesTheDecalPass) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-render");
    ASSERT_EQ(runBench("render --quick --groups count --frames 1 --json " + dir + "/r.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/r.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/r.json");
    ASSERT_EQ(j["rows"].size(), 2u);
    for (const auto& row : j["rows"]) {
        EXPECT_EQ(row["decals_drawn"], row["visible"]);
        EXPECT_FALSE(row["decal_pass_skipped"].get<bool>());
        EXPECT_GE(row["decal_ms"].get<double>(), 0.0);
    }
}

// --rounds N measures every row N times over: each row's frames are those of all its rounds.
TEST(BenchSmoke, RenderRoundsMeasureEveryRowInEachRound) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-render-rounds");
    ASSERT_EQ(runBench("render --quick --groups count --frames 1 --rounds 2 --json " + dir + "/r.json",
                       dir + "/log"),
              0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/r.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/r.json");
    EXPECT_EQ(j["rounds"], 2);
    ASSERT_EQ(j["rows"].size(), 2u);
    for (const auto& row : j["rows"]) {
        EXPECT_EQ(row["frames"], 2) << row.dump();
        EXPECT_GE(row["decal_ms"].get<double>(), 0.0);
    }
    EXPECT_EQ(runBench("render --quick --rounds 0", dir + "/log"), 2) << readAll(dir + "/log");
}

TEST(BenchSmoke, SurfaceQuickTimesTheSearchAndFindsEveryLineOnTheFloor) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-surface");
    ASSERT_EQ(runBench("surface --quick --json " + dir + "/s.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/s.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/s.json");
    ASSERT_EQ(j["rows"].size(), 4u);
    EXPECT_GT(j["frame_gpu_ms"].get<double>(), 0.0);
    for (const auto& row : j["rows"]) {
        EXPECT_EQ(row["found"], row["lines"]) << "every line crosses the floor in view";
        EXPECT_GT(row["ms"].get<double>(), 0.0);
    }
}

TEST(BenchSmoke, CharactersQuickTimesTheFrameWithAndWithoutTheirDecals) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-characters");
    ASSERT_EQ(runBench("characters --quick --frames 3 --decals 20 --json " + dir + "/c.json", dir + "/log"),
              0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/c.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/c.json");
    ASSERT_EQ(j["rows"].size(), 1u);
    const nlohmann::json& row = j["rows"][0];
    EXPECT_EQ(row["characters"], 1);
    EXPECT_EQ(row["decals"], 20) << "every decal asked for lands on the character";
    for (const char* key :
         {"setpose_ms", "update_ms", "render_ms", "decal_pass_ms", "frame_ms", "baseline_frame_ms"})
        EXPECT_GE(row[key].get<double>(), 0.0) << key;
}

TEST(BenchSmoke, RenderPathsTimeEveryPathOfTheProjectorWithTheSameDecals) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-paths");
    ASSERT_EQ(runBench("render --quick --groups paths --frames 1 --max-seconds 60 --json " + dir + "/p.json",
                       dir + "/log"),
              0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/p.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/p.json");
    ASSERT_EQ(j["rows"].size(), 8u); // renderer, blend, DBuffer, forward at two counts
    for (const auto& row : j["rows"]) {
        ASSERT_FALSE(row.contains("error")) << row.dump();
        EXPECT_EQ(row["decals_drawn"], row["visible"]) << row["feature"];
        EXPECT_GE(row["decal_ms"].get<double>(), 0.0);
        if (row["feature"] != "renderer") {
            EXPECT_GE(row["projector_ms"].get<double>(), 0.0);
        }
    }
    EXPECT_TRUE(j["targets"].contains("paths_blend_over_renderer_100"));
}

TEST(BenchSmoke, VolumetricQuickDrawsEveryCraterInAFewInstancedDraws) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("bench-volumetric");
    ASSERT_EQ(runBench("volumetric --quick --frames 1 --json " + dir + "/v.json", dir + "/log"), 0)
        << readAll(dir + "/log");
    const nlohmann::json j = readJson(dir + "/v.json");
    ASSERT_TRUE(j.is_object() && j["rows"].is_array()) << readAll(dir + "/v.json");
    ASSERT_EQ(j["rows"].size(), 2u);
    for (const auto& row : j["rows"]) {
        // Geometry and lighting, then two draws per crater variant and winding in use (4 variants).
        EXPECT_LE(row["volumetric_draws"].get<int>(), 2 + 2 * 4) << row.dump();
        EXPECT_GT(row["volumetric_pass_ms"].get<double>(), 0.0) << row.dump();
        EXPECT_GT(row["ratio"].get<double>(), 0.0) << row.dump();
    }
}

TEST(BenchTool, RefusesARepeatedOptionAMissingValueAndNumbersThatAreNotDecimal) {
    const std::string dir = test::scratchDir("bench-usage");
    const std::string log = dir + "/log";
    EXPECT_EQ(runBench("load --repeat 3 --repeat 4", log), 2);
    EXPECT_NE(readAll(log).find("--repeat given twice"), std::string::npos) << readAll(log);
    for (const char* bad :
         {"memory --json --quick", "pose --frames 0x10", "pose --frames ' 5'", "placement --cone ' 1'",
          "placement --cone 0x1", "stress --seed ' 5'", "stress --seed 99999999999999999999",
          "stress --quick --quick", "stress --json --quick"})
        EXPECT_EQ(runBench(bad, log), 2) << bad << ": " << readAll(log);
}

TEST(BenchTool, ChecksItsJsonFileBeforeTheWork) {
    const std::string dir = test::scratchDir("bench-json");
    const std::string log = dir + "/log", json = " --json " + dir + "/no/such/folder/x.json";
    EXPECT_EQ(runBench("persistence --quick --decals 10 --repeat 1" + json, log), 2) << readAll(log);
    EXPECT_NE(readAll(log).find("does not exist"), std::string::npos) << readAll(log);
    EXPECT_EQ(runBench("stress --quick --case degenerate --no-gpu" + json, log), 2) << readAll(log);
    EXPECT_EQ(runBench("persistence --quick --decals 10 --repeat 1 --json " + dir, log), 2) << readAll(log);
}

TEST(BenchTool, PlacementRefusesAFilterThatIsNotARegularExpression) {
    const std::string dir = test::scratchDir("bench-filter");
    EXPECT_EQ(runBench("placement --quick --filter '('", dir + "/log"), 2) << readAll(dir + "/log");
    EXPECT_NE(readAll(dir + "/log").find("--filter"), std::string::npos);
}

TEST(BenchTool, StressRefusesAPlaceToolThatIsNotAnExecutableFile) {
    const std::string dir = test::scratchDir("bench-place-tool");
    const std::string log = dir + "/log";
    for (const std::string& tool : {dir + "/nonexistent", dir})
        EXPECT_EQ(runBench("stress --quick --case far-tool --no-gpu --place-tool " + tool, log), 2)
            << readAll(log);
    EXPECT_NE(readAll(log).find("is not an executable file"), std::string::npos) << readAll(log);
}
