// The spatter-place contract (docs/PLACEMENT.md, spatter-place --help) on every scene of the shared
// data: one record per ray line in input order, placed records with a unit right-handed frame on
// their ray, the others with a reason and nothing else, a summary that adds up, exit code 0.

#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

using namespace spatter;

namespace {

// Every scene file below the shared data directory, sorted.
std::vector<std::string> sharedScenes(const std::string& root) {
    static const std::set<std::string> kExtensions = {".gltf", ".glb", ".obj", ".ply", ".off", ".stl"};
    std::vector<std::string> scenes;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root))
        if (e.is_regular_file() && kExtensions.count(e.path().extension().string()))
            scenes.push_back(e.path().string());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

struct RayLine {
    bool ray = true; // false: a line that is not a ray (comment, blank)
    glm::dvec3 o{0.0}, d{0.0};
};

// Six 16-ray bursts at the scene's centre from outside its bounds (spawnBatch traces them as
// packets), a ray away from it, comments, a blank line, a line that does not parse and a ray with a
// zero direction. Written to `path`; returns the lines.
std::vector<RayLine> writeRays(const DBounds& b, const std::string& path) {
    const glm::dvec3 c = 0.5 * (b.min + b.max);
    const double r = std::max(glm::length(b.max - b.min), 1e-3);
    std::ofstream out(path);
    out.precision(17);
    std::vector<RayLine> lines;
    auto ray = [&](const glm::dvec3& o, const glm::dvec3& d) {
        out << o.x << ' ' << o.y << ' ' << o.z << ' ' << d.x << ' ' << d.y << ' ' << d.z << '\n';
        lines.push_back({true, o, d});
    };
    out << "# bursts at the centre\n";
    lines.push_back({false});
    const glm::dvec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::dvec3& a : axes) {
        const glm::dvec3 eye = c + 1.5 * r * glm::normalize(a + glm::dvec3(0.1, 0.2, 0.3));
        for (int i = 0; i < 16; ++i) {
            const glm::dvec3 jitter = 0.01 * r * glm::dvec3((i % 4) - 1.5, (i / 4) - 1.5, 0.5 * (i % 3));
            ray(eye, (c + jitter - eye) * 2.0); // not unit length
        }
    }
    ray(c + 2.0 * r * glm::dvec3(0, 1, 0), glm::dvec3(0, 1, 0)); // away from everything
    out << "\n";
    lines.push_back({false});
    out << "1 2 three 4 5 6\n";
    lines.push_back({true});
    out << "0 0 0 0 0 0  # zero direction\n";
    lines.push_back({true});
    return lines;
}

std::vector<double> vec(const nlohmann::json& j) {
    return j.is_array() && j.size() == 3 && j[0].is_number() && j[1].is_number() && j[2].is_number()
               ? std::vector<double>{j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}
               : std::vector<double>{};
}

glm::dvec3 toVec(const std::vector<double>& v) {
    return {v[0], v[1], v[2]};
}

// Checks the records of one run against the rays; counts placed records.
void checkRecords(const std::string& scene, const Scene& loaded, const std::vector<RayLine>& lines,
                  const std::string& records, size_t& placed) {
    std::set<std::string> names;
    for (const SceneObject& o : loaded.objects)
        names.insert(o.name);
    std::vector<RayLine> rays;
    for (const RayLine& l : lines)
        if (l.ray) rays.push_back(l);
    std::istringstream in(records);
    size_t n = 0;
    for (std::string line; std::getline(in, line); ++n) {
        SCOPED_TRACE(scene + ", record " + std::to_string(n) + ": " + line);
        const nlohmann::json rec = nlohmann::json::parse(line, nullptr, false);
        ASSERT_TRUE(rec.is_object());
        ASSERT_LT(n, rays.size());
        ASSERT_EQ(rec.value("ray", -1), int(n));
        const std::string status = rec.value("status", "");
        ASSERT_TRUE(rec.contains("reason") && rec["reason"].is_string());
        if (status != "placed") {
            EXPECT_TRUE(status == "missed" || status == "rejected");
            EXPECT_FALSE(rec["reason"].get<std::string>().empty());
            EXPECT_EQ(rec.size(), 3u);
            continue;
        }
        placed++;
        EXPECT_EQ(rec["reason"], "");
        EXPECT_TRUE(names.count(rec.value("object", std::string("?"))));
        EXPECT_TRUE(rec["object_id"].is_number_unsigned() && rec["object_id"].get<unsigned>() <= 255u);
        EXPECT_TRUE(rec["decal_id"].is_number_unsigned());
        const std::vector<double> p = vec(rec["position"]), nv = vec(rec["normal"]), tv = vec(rec["tangent"]),
                                  bv = vec(rec["bitangent"]);
        ASSERT_TRUE(!p.empty() && !nv.empty() && !tv.empty() && !bv.empty());
        const glm::dvec3 nrm = toVec(nv), t = toVec(tv), b = toVec(bv);
        EXPECT_NEAR(glm::length(nrm), 1.0, 1e-6);
        EXPECT_NEAR(glm::length(t), 1.0, 1e-6);
        EXPECT_NEAR(glm::length(b), 1.0, 1e-6);
        EXPECT_NEAR(glm::dot(nrm, t), 0.0, 1e-6);
        EXPECT_NEAR(glm::length(glm::cross(t, b) - nrm), 0.0, 2e-6); // right-handed
        const RayLine& r = rays[n];
        const glm::dvec3 u = glm::normalize(r.d), fromOrigin = toVec(p) - r.o;
        // On the ray, to the float precision in which decals keep their centres.
        const double slack = 1e-6 * (glm::length(toVec(p)) + glm::length(fromOrigin));
        EXPECT_LE(glm::length(glm::cross(fromOrigin, u)), slack); // on the ray
        EXPECT_GT(glm::dot(fromOrigin, u), 0.0);
        EXPECT_LE(glm::dot(nrm, u), 0.0); // facing the ray
        const std::vector<double> pv = vec(rec["projection"]);
        ASSERT_FALSE(pv.empty());
        EXPECT_LT(glm::length(toVec(pv) + u), 2e-3); // along the reversed ray (within 85 degrees)
        ASSERT_TRUE(rec["size"].is_array() && rec["size"].size() == 2u);
        EXPECT_NEAR(rec["size"][0].get<double>(), 0.05, 1e-7); // --size, in world units
        EXPECT_NEAR(rec["size"][1].get<double>(), 0.05, 1e-7);
        EXPECT_EQ(rec["max_angle_deg"], 85);
        EXPECT_GE(rec["half_depth"].get<double>(), rec["proxy_error_bound"].get<double>());
        EXPECT_EQ(rec["proxy_error_bound"], 0.0); // --proxy render
    }
    EXPECT_EQ(n, rays.size()) << scene;
}

} // namespace

TEST(SpatterPlaceContract, EverySharedSceneGivesOneRecordPerRayInOrder) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built (SPATTER_BUILD_APPS=OFF)";
    SPATTER_REQUIRE_SHARED(root, ".");
    const std::vector<std::string> scenes = sharedScenes(root);
    ASSERT_GE(scenes.size(), 10u) << root;
    const std::string dir = test::scratchDir("place-contract");
    for (const std::string& scene : scenes) {
        SCOPED_TRACE(scene);
        Result<Scene> loaded = loadScene(scene);
        ASSERT_TRUE(loaded) << loaded.error();
        const std::vector<RayLine> lines = writeRays(loaded->worldBounds(), dir + "/rays.txt");
        const test::PlaceToolRun run =
            test::runPlaceTool("'" + scene + "' --rays '" + dir +
                                   "/rays.txt' --size 0.05 --max-angle 85 --proxy render --summary",
                               dir);
        ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.records;
        size_t placed = 0;
        checkRecords(scene, loaded.value(), lines, run.records, placed);
        EXPECT_GE(placed, 16u) << "at least one burst lands";

        const nlohmann::json& s = run.summary;
        ASSERT_TRUE(s.is_object());
        const size_t rays =
            size_t(std::count_if(lines.begin(), lines.end(), [](const RayLine& l) { return l.ray; }));
        EXPECT_EQ(s["rays"], rays);
        EXPECT_EQ(s["placed"], placed);
        size_t rejected = 0;
        for (const auto& [reason, count] : s["rejected"].items())
            rejected += count.get<size_t>();
        EXPECT_EQ(s["placed"].get<size_t>() + s["missed"].get<size_t>() + rejected, rays);
        EXPECT_EQ(s["rejected"]["unparseable"], 1);
        EXPECT_EQ(s["rejected"]["invalid_ray"], 1);
        EXPECT_GE(s["missed"].get<size_t>(), 1u);
        EXPECT_EQ(s["render_triangles"], loaded->triangleCount());
        EXPECT_EQ(s["proxy_triangles"], s["render_triangles"]); // every shared object receives decals
        EXPECT_GE(s["seconds"].get<double>(), 0.0);
    }
    const test::PlaceToolRun missing = test::runPlaceTool("'" + dir + "/no-such-scene.obj'", dir);
    ASSERT_TRUE(WIFEXITED(missing.status));
    EXPECT_EQ(WEXITSTATUS(missing.status), 1);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
}
