// Faults from outside: no GL context, damaged proxy cache entries, scene files that change on disk.

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/ProxyCache.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <vector>

using namespace spatter;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

std::string readText(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void writeText(const std::string& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << bytes;
}

std::string objText(const Mesh& mesh) {
    std::string s;
    char line[128];
    for (const glm::vec3& p : mesh.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        s += line;
    }
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        std::snprintf(line, sizeof line, "f %u %u %u\n", mesh.indices[i] + 1, mesh.indices[i + 1] + 1,
                      mesh.indices[i + 2] + 1);
        s += line;
    }
    return s;
}

// A mesh large enough to be simplified (and so cached) by buildProxy.
Mesh bumpySphere(float bump) {
    Mesh m = makeSphere(1.0f, 16, 32); // 992 triangles
    displace(m, [bump](const glm::vec3& p, const glm::vec3&) { return bump * std::sin(7.0f * p.x) * p.y; });
    return m;
}

ProxySettings cachedSettings(const std::string& dir) {
    ProxySettings s;
    s.tolerance = 0.02f;
    s.cacheDirectory = dir;
    return s;
}

bool notesMention(const Proxy& p, const std::string& text) {
    for (const std::string& n : p.notes)
        if (n.find(text) != std::string::npos) return true;
    return false;
}

struct ProcessResult {
    bool exited = false; // ended by exit(), not by a signal
    int code = -1;
    std::string output; // stdout and stderr
};

// Runs `command` through the shell with its output captured.
ProcessResult run(const std::string& command, const std::string& scratch) {
    const std::string log = scratch + "/output.txt";
    const int status = std::system((command + " >" + log + " 2>&1").c_str());
    ProcessResult r;
    r.exited = status != -1 && WIFEXITED(status);
    r.code = r.exited ? WEXITSTATUS(status) : -1;
    r.output = readText(log);
    return r;
}

// Environment under which libglvnd's EGL finds no vendor library, so no EGL display or device exists.
const char* const kNoEgl = "env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json "
                           "__EGL_VENDOR_LIBRARY_DIRS=/nonexistent EGL_PLATFORM=surfaceless ";

} // namespace

// --- no GL context -----------------------------------------------------------------------------------

#ifdef SPATTER_RENDER_TOOL
TEST(NoGlContext, RenderToolSaysSoAndExitsWithOne) {
    const std::string dir = test::scratchDir("fault-render");
    const ProcessResult r = run(std::string(kNoEgl) + SPATTER_RENDER_TOOL +
                                    " builtin:gallery --size 64x64 --out " + dir + "/out.png",
                                dir);
    ASSERT_TRUE(r.exited) << "killed by a signal:\n" << r.output;
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("spatter-render: "));
    EXPECT_THAT(r.output, HasSubstr("headless GL"));
    EXPECT_FALSE(fs::exists(dir + "/out.png"));
}

TEST(NoGlContext, GalleryWithoutDisplayOrEglSaysSoAndExitsWithOne) {
    const std::string dir = test::scratchDir("fault-gallery");
    // A display that does not exist: the window fails, the headless fallback finds no EGL either.
    const ProcessResult r =
        run(std::string(kNoEgl) + "DISPLAY=:97 WAYLAND_DISPLAY= " + SPATTER_GALLERY +
                " --shots 2 --size 64x64 --tolerance 0 --out " + dir + "/out --cache " + dir + "/cache",
            dir);
    ASSERT_TRUE(r.exited) << "killed by a signal:\n" << r.output;
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_THAT(r.output, HasSubstr("no window"));
    EXPECT_THAT(r.output, HasSubstr("no OpenGL 4.5 context"));
}
#endif

// --- proxy cache entries --------------------------------------------------------------------------

TEST(ProxyCacheFaults, TruncatedOrCorruptEntryIsRebuiltAndRewritten) {
    const std::string dir = test::scratchDir("fault-cache");
    const Mesh mesh = bumpySphere(0.05f);
    const ProxySettings s = cachedSettings(dir);
    Result<Proxy> first = buildProxy(mesh, s);
    ASSERT_TRUE(first) << first.error();
    ASSERT_EQ(first->source, ProxySource::Simplified);
    ASSERT_FALSE(first->cached);
    const std::string entry = proxyCachePath(dir, proxyCacheKey(mesh, s, nullptr));
    const std::string good = readText(entry);
    ASSERT_GT(good.size(), 100u);

    std::string flipped = good;
    flipped[flipped.size() / 2] = char(flipped[flipped.size() / 2] ^ 0x5a);
    std::string garbage(good.size(), '\0');
    for (size_t i = 0; i < garbage.size(); ++i)
        garbage[i] = char(i * 131 + 7);
    const std::vector<std::pair<const char*, std::string>> damages = {
        {"truncated by one byte", good.substr(0, good.size() - 1)},
        {"empty", ""},
        {"one byte flipped", flipped},
        {"garbage of the right size", garbage}};
    for (const auto& [what, bytes] : damages) {
        SCOPED_TRACE(what);
        writeText(entry, bytes);
        Result<Proxy> rebuilt = buildProxy(mesh, s);
        ASSERT_TRUE(rebuilt) << rebuilt.error();
        EXPECT_FALSE(rebuilt->cached);
        EXPECT_TRUE(notesMention(rebuilt.value(), "corrupt"))
            << (rebuilt->notes.empty() ? "" : rebuilt->notes[0]);
        EXPECT_TRUE(notesMention(rebuilt.value(), "rebuilt"));
        EXPECT_EQ(rebuilt->mesh.positions, first->mesh.positions);
        EXPECT_EQ(rebuilt->mesh.indices, first->mesh.indices);
        EXPECT_EQ(rebuilt->errorBound, first->errorBound);
        // The entry was written again and the next build loads it.
        EXPECT_EQ(readText(entry), good);
        Result<Proxy> again = buildProxy(mesh, s);
        ASSERT_TRUE(again) << again.error();
        EXPECT_TRUE(again->cached);
        EXPECT_EQ(again->mesh.positions, first->mesh.positions);
        EXPECT_EQ(again->errorBound, first->errorBound);
        EXPECT_EQ(again->drawnNormals.packed(), first->drawnNormals.packed());
    }
    EXPECT_TRUE(first->drawnNormals.fits(first->mesh.triangleCount()));
}

TEST(ProxyCacheFaults, SceneFileChangedOnDiskInvalidatesItsEntry) {
    const std::string dir = test::scratchDir("fault-scene-change");
    const std::string path = dir + "/rock.obj";
    const ProxySettings s = cachedSettings(dir + "/cache");
    auto buildFromFile = [&]() -> Result<Proxy> {
        Result<Scene> scene = loadScene(path);
        if (!scene) return fail(scene.error());
        return buildProxy(*scene->objects.at(0).mesh, s);
    };

    writeText(path, objText(bumpySphere(0.05f)));
    Result<Proxy> first = buildFromFile();
    ASSERT_TRUE(first) << first.error();
    ASSERT_FALSE(first->cached);
    Result<Proxy> second = buildFromFile();
    ASSERT_TRUE(second) << second.error();
    EXPECT_TRUE(second->cached); // unchanged file: the entry is used

    // The file changes between runs: the old entry must not be used.
    writeText(path, objText(bumpySphere(0.15f)));
    Result<Proxy> changed = buildFromFile();
    ASSERT_TRUE(changed) << changed.error();
    EXPECT_FALSE(changed->cached);
    EXPECT_NE(changed->mesh.positions, first->mesh.positions);
    Result<Scene> now = loadScene(path);
    ASSERT_TRUE(now) << now.error();
    const Bounds nowBounds = now->objects[0].mesh->bounds(), proxyBounds = changed->mesh.bounds();
    for (int k = 0; k < 3; ++k) { // the proxy follows the new geometry, within its error bound
        EXPECT_NEAR(proxyBounds.min[k], nowBounds.min[k], changed->errorBound + 1e-4);
        EXPECT_NEAR(proxyBounds.max[k], nowBounds.max[k], changed->errorBound + 1e-4);
    }
    Result<Proxy> changedAgain = buildFromFile();
    ASSERT_TRUE(changedAgain) << changedAgain.error();
    EXPECT_TRUE(changedAgain->cached);
    EXPECT_EQ(changedAgain->mesh.positions, changed->mesh.positions);

    // Changed back: the first entry is still valid for the first contents.
    writeText(path, objText(bumpySphere(0.05f)));
    Result<Proxy> back = buildFromFile();
    ASSERT_TRUE(back) << back.error();
    EXPECT_TRUE(back->cached);
    EXPECT_EQ(back->mesh.positions, first->mesh.positions);
}

TEST(ProxyCacheFaults, EntryOfAnotherMeshUnderThisKeyIsRejected) {
    const std::string dir = test::scratchDir("fault-cache-swap");
    const ProxySettings s = cachedSettings(dir);
    const Mesh a = bumpySphere(0.05f), b = bumpySphere(0.15f);
    ASSERT_TRUE(buildProxy(a, s));
    ASSERT_TRUE(buildProxy(b, s));
    const std::string entryA = proxyCachePath(dir, proxyCacheKey(a, s, nullptr));
    const std::string entryB = proxyCachePath(dir, proxyCacheKey(b, s, nullptr));
    const std::string bytesA = readText(entryA);
    writeText(entryA, readText(entryB)); // b's valid entry copied over a's
    Result<Proxy> rebuilt = buildProxy(a, s);
    ASSERT_TRUE(rebuilt) << rebuilt.error();
    EXPECT_FALSE(rebuilt->cached);
    EXPECT_TRUE(notesMention(rebuilt.value(), "rebuilt"));
    EXPECT_EQ(readText(entryA), bytesA);
}
