#include "spatter/core/ProxyCache.hpp"

#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

using namespace spatter;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

Proxy sampleProxy() {
    Proxy p;
    p.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    p.mesh.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    computeNormals(p.mesh);
    p.source = ProxySource::Simplified;
    p.backend = ProxyBackend::OpenMesh;
    p.tolerance = 0.25;
    p.toleranceMet = true;
    p.errorBound = 0.125;
    p.proxyToRenderMax = 0.1;
    p.renderToProxyMax = 0.05;
    p.samplingMargin = 0.02;
    p.samples = 12345;
    p.inputTriangles = 5000;
    p.proxyTriangles = 4;
    p.attempts = 2;
    std::vector<DrawnNormals::Packed> drawn;
    for (int16_t i = 0; i < 36; ++i) // 9 pieces for each of the 4 triangles, negative values among them
        drawn.push_back({int16_t(1000 * i - 17000), int16_t(-32767 + i), int16_t(i * i)});
    p.drawnNormals = DrawnNormals(drawn);
    return p;
}

std::vector<char> readAll(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void writeAll(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}

Mesh tetrahedron() {
    return sampleProxy().mesh;
}

} // namespace

TEST(ProxyCache, RoundTripsAProxy) {
    const std::string dir = test::scratchDir("cache-roundtrip") + "/nested/dir";
    const Proxy p = sampleProxy();
    ASSERT_TRUE(storeCachedProxy(dir, 42, p).ok());
    Result<Proxy> q = loadCachedProxy(dir, 42);
    ASSERT_TRUE(q) << q.error();
    EXPECT_TRUE(q->cached);
    EXPECT_EQ(q->mesh.positions, p.mesh.positions);
    EXPECT_EQ(q->mesh.normals, p.mesh.normals);
    EXPECT_EQ(q->mesh.indices, p.mesh.indices);
    EXPECT_EQ(q->source, p.source);
    EXPECT_EQ(q->backend, p.backend);
    EXPECT_EQ(q->tolerance, p.tolerance);
    EXPECT_EQ(q->toleranceMet, p.toleranceMet);
    EXPECT_EQ(q->errorBound, p.errorBound);
    EXPECT_EQ(q->proxyToRenderMax, p.proxyToRenderMax);
    EXPECT_EQ(q->renderToProxyMax, p.renderToProxyMax);
    EXPECT_EQ(q->samplingMargin, p.samplingMargin);
    EXPECT_EQ(q->samples, p.samples);
    EXPECT_EQ(q->inputTriangles, p.inputTriangles);
    EXPECT_EQ(q->proxyTriangles, p.proxyTriangles);
    EXPECT_EQ(q->attempts, p.attempts);
    EXPECT_EQ(q->drawnNormals.packed(), p.drawnNormals.packed());
    // Written through a temporary file that is renamed: nothing else is left in the directory.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(ProxyCache, AnEntryWhoseDrawnNormalsDoNotFitItsTrianglesIsCorrupt) {
    const std::string dir = test::scratchDir("cache-drawn-normals");
    Proxy p = sampleProxy();
    std::vector<DrawnNormals::Packed> fewer = p.drawnNormals.packed();
    fewer.pop_back();
    p.drawnNormals = DrawnNormals(fewer);
    ASSERT_TRUE(storeCachedProxy(dir, 7, p).ok());
    Result<Proxy> q = loadCachedProxy(dir, 7);
    ASSERT_FALSE(q);
    EXPECT_THAT(q.error(), HasSubstr("corrupt: 35 drawn normals for 4 triangles"));
    p.drawnNormals = DrawnNormals(); // none at all is an entry of its own (the render mesh as proxy)
    ASSERT_TRUE(storeCachedProxy(dir, 8, p).ok());
    q = loadCachedProxy(dir, 8);
    ASSERT_TRUE(q) << q.error();
    EXPECT_TRUE(q->drawnNormals.empty());
}

TEST(ProxyCache, MissingEntryIsAMiss) {
    const std::string dir = test::scratchDir("cache-missing");
    Result<Proxy> q = loadCachedProxy(dir, 7);
    ASSERT_FALSE(q);
    EXPECT_THAT(q.error(), HasSubstr("no cache entry"));
}

TEST(ProxyCache, DetectsAFlippedByteAnywhere) {
    const std::string dir = test::scratchDir("cache-flip");
    ASSERT_TRUE(storeCachedProxy(dir, 9, sampleProxy()).ok());
    const std::string path = proxyCachePath(dir, 9);
    const std::vector<char> good = readAll(path);
    for (size_t at = 0; at < good.size(); ++at) {
        std::vector<char> bad = good;
        bad[at] = char(bad[at] ^ 0x10);
        writeAll(path, bad);
        Result<Proxy> q = loadCachedProxy(dir, 9);
        ASSERT_FALSE(q) << "byte " << at;
        EXPECT_THAT(q.error(), HasSubstr("corrupt")) << "byte " << at;
    }
}

TEST(ProxyCache, DetectsTruncationAndExtraBytes) {
    const std::string dir = test::scratchDir("cache-truncate");
    ASSERT_TRUE(storeCachedProxy(dir, 9, sampleProxy()).ok());
    const std::string path = proxyCachePath(dir, 9);
    const std::vector<char> good = readAll(path);
    for (size_t size : {size_t(0), size_t(3), size_t(60), good.size() / 2, good.size() - 1}) {
        writeAll(path, std::vector<char>(good.begin(), good.begin() + std::ptrdiff_t(size)));
        Result<Proxy> q = loadCachedProxy(dir, 9);
        ASSERT_FALSE(q) << size << " bytes";
        EXPECT_THAT(q.error(), HasSubstr("corrupt"));
    }
    std::vector<char> longer = good;
    longer.push_back('x');
    writeAll(path, longer);
    EXPECT_THAT(loadCachedProxy(dir, 9).error(), HasSubstr("corrupt"));
}

TEST(ProxyCache, RejectsAnEntryStoredUnderAnotherKey) {
    const std::string dir = test::scratchDir("cache-key");
    ASSERT_TRUE(storeCachedProxy(dir, 1, sampleProxy()).ok());
    fs::copy_file(proxyCachePath(dir, 1), proxyCachePath(dir, 2));
    EXPECT_THAT(loadCachedProxy(dir, 2).error(), HasSubstr("another key"));
}

TEST(ProxyCache, ReportsAnUnwritableDirectory) {
    const std::string dir = test::scratchDir("cache-unwritable");
    const std::string file = dir + "/not-a-directory";
    writeAll(file, {'x'});
    Status s = storeCachedProxy(file, 3, sampleProxy());
    ASSERT_FALSE(s.ok());
    EXPECT_THAT(s.error(), HasSubstr("not-a-directory"));
}

TEST(ProxyCache, KeyFollowsGeometryAndSettingsOnly) {
    const Mesh m = tetrahedron();
    const ProxySettings s;
    const uint64_t key = proxyCacheKey(m, s, nullptr);
    EXPECT_EQ(proxyCacheKey(m, s, nullptr), key);

    Mesh moved = m;
    moved.positions[2].y += 1e-6f;
    EXPECT_NE(proxyCacheKey(moved, s, nullptr), key);
    Mesh reordered = m;
    std::swap(reordered.indices[0], reordered.indices[1]);
    EXPECT_NE(proxyCacheKey(reordered, s, nullptr), key);
    EXPECT_NE(proxyCacheKey(m, s, &m), key);

    Mesh decorated = m; // attributes that do not change the proxy
    decorated.uvs.assign(m.positions.size(), glm::vec2(0.5f));
    decorated.normals.assign(m.positions.size(), glm::vec3(1, 0, 0));
    EXPECT_EQ(proxyCacheKey(decorated, s, nullptr), key);

    ProxySettings other = s;
    other.cacheDirectory = "/elsewhere";
    EXPECT_EQ(proxyCacheKey(m, other, nullptr), key);
    other = s;
    other.tolerance *= 2.0f;
    EXPECT_NE(proxyCacheKey(m, other, nullptr), key);
    other = s;
    other.backend = ProxyBackend::MeshOpt;
    EXPECT_NE(proxyCacheKey(m, other, nullptr), key);
    other = s;
    other.maxTriangles = 10;
    EXPECT_NE(proxyCacheKey(m, other, nullptr), key);
    other = s;
    other.keepSharpFeatures = !s.keepSharpFeatures;
    EXPECT_NE(proxyCacheKey(m, other, nullptr), key);
}

TEST(ProxyCache, Fnv1aMatchesTheReferenceValues) {
    EXPECT_EQ(fnv1a("", 0), 0xcbf29ce484222325ULL);
    EXPECT_EQ(fnv1a("a", 1), 0xaf63dc4c8601ec8cULL);
    EXPECT_EQ(fnv1a("foobar", 6), 0x85944171f73967e8ULL);
}
