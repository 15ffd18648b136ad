#include "spatter/core/ProxyCache.hpp"

#include "ValueHasher.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

namespace spatter {

namespace fs = std::filesystem;

using detail::doubleBits;
using detail::floatBits;

namespace {

constexpr char kMagic[4] = {'S', 'P', 'X', 'C'};
constexpr uint32_t kFormatVersion = 2;
// Part of every key: bump it whenever the builder gives a different proxy for the same input, so
// that entries written by an older builder are never loaded.
constexpr uint32_t kBuilderVersion = 7;
// Bytes before the vertex data (magic through the count of drawn normals), and the checksum after it.
constexpr size_t kHeaderSize = 4 + 4 + 8 + 4 * 4 + 8 * 2 + 8 * 5 + 4 * 3;
constexpr size_t kDrawnNormalSize = 6; // three 16-bit fractions
constexpr size_t kChecksumSize = 8;

// Little-endian byte writer and bounds-checked reader.
struct Writer {
    std::vector<unsigned char> bytes;
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i)
            bytes.push_back((unsigned char)(v >> (8 * i)));
    }
    void u64(uint64_t v) {
        for (int i = 0; i < 8; ++i)
            bytes.push_back((unsigned char)(v >> (8 * i)));
    }
    void i16(int16_t v) {
        const uint16_t u = uint16_t(v);
        bytes.push_back((unsigned char)(u & 0xffu));
        bytes.push_back((unsigned char)(u >> 8));
    }
    void f32(float v) { u32(floatBits(v)); }
    void f64(double v) { u64(doubleBits(v)); }
};

struct Reader {
    const unsigned char* data;
    size_t size;
    size_t at = 0;
    bool u32(uint32_t& v) {
        if (size - at < 4) return false;
        v = 0;
        for (int i = 0; i < 4; ++i)
            v |= uint32_t(data[at + size_t(i)]) << (8 * i);
        at += 4;
        return true;
    }
    bool u64(uint64_t& v) {
        if (size - at < 8) return false;
        v = 0;
        for (int i = 0; i < 8; ++i)
            v |= uint64_t(data[at + size_t(i)]) << (8 * i);
        at += 8;
        return true;
    }
    bool i16(int16_t& v) {
        if (size - at < 2) return false;
        v = int16_t(uint16_t(data[at] | (uint16_t(data[at + 1]) << 8)));
        at += 2;
        return true;
    }
    bool f32(float& v) {
        uint32_t u;
        if (!u32(u)) return false;
        std::memcpy(&v, &u, 4);
        return true;
    }
    bool f64(double& v) {
        uint64_t u;
        if (!u64(u)) return false;
        std::memcpy(&v, &u, 8);
        return true;
    }
};

} // namespace

uint64_t fnv1a(const void* data, size_t size, uint64_t hash) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        hash ^= p[i];
        hash *= 0x100000001b3ULL;
    }
    return hash;
}

uint64_t proxyCacheKey(const Mesh& render, const ProxySettings& s, const Mesh* authoredCollider) {
    detail::ValueHasher h;
    h.u32(kFormatVersion);
    h.u32(kBuilderVersion);
    h.mesh(render);
    h.u32(authoredCollider ? 1 : 0);
    if (authoredCollider) h.mesh(*authoredCollider);
    h.f32(s.tolerance);
    h.u32(s.toleranceRelative);
    h.u32(s.maxTriangles);
    h.u32(uint32_t(s.backend));
    h.u32(s.keepBoundaries);
    h.u32(s.keepSharpFeatures);
    h.f32(s.featureAngleDegrees);
    h.u32(s.smallMeshTriangles);
    h.f32(s.marginFraction);
    h.u32(s.maxAttempts);
    return h.h;
}

std::string proxyCachePath(const std::string& directory, uint64_t key) {
    char name[32];
    std::snprintf(name, sizeof(name), "proxy-%016llx.bin", (unsigned long long)key);
    return (fs::path(directory) / name).string();
}

Result<Proxy> loadCachedProxy(const std::string& directory, uint64_t key) {
    const std::string path = proxyCachePath(directory, key);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return fail("no cache entry " + path);
    const uintmax_t fileSize = fs::file_size(path, ec);
    if (ec) return fail("cache entry " + path + " cannot be read: " + ec.message());
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail("cache entry " + path + " cannot be opened");
    std::vector<unsigned char> bytes(static_cast<size_t>(fileSize));
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    if (size_t(in.gcount()) != bytes.size()) return fail("cache entry " + path + " cannot be read");
    auto corrupt = [&](const std::string& what) {
        return fail("cache entry " + path + " is corrupt: " + what);
    };
    if (bytes.size() < kHeaderSize + kChecksumSize)
        return corrupt("truncated (" + std::to_string(bytes.size()) + " bytes)");
    if (std::memcmp(bytes.data(), kMagic, 4) != 0) return corrupt("bad magic");

    Reader r{bytes.data(), bytes.size(), 4};
    uint32_t version = 0, source = 0, backend = 0, flags = 0, attempts = 0, vertexCount = 0, indexCount = 0,
             drawnCount = 0;
    uint64_t storedKey = 0, inputTriangles = 0, samples = 0;
    Proxy p;
    // The size was checked against the header above, so these reads cannot fail.
    r.u32(version);
    r.u64(storedKey);
    r.u32(source);
    r.u32(backend);
    r.u32(flags);
    r.u32(attempts);
    r.u64(inputTriangles);
    r.u64(samples);
    r.f64(p.tolerance);
    r.f64(p.errorBound);
    r.f64(p.proxyToRenderMax);
    r.f64(p.renderToProxyMax);
    r.f64(p.samplingMargin);
    r.u32(vertexCount);
    r.u32(indexCount);
    r.u32(drawnCount);
    if (version != kFormatVersion) return corrupt("format version " + std::to_string(version));
    if (storedKey != key) return corrupt("it holds another key");
    const uint64_t expected = uint64_t(kHeaderSize) + uint64_t(vertexCount) * 24u +
                              uint64_t(indexCount) * 4u + uint64_t(drawnCount) * kDrawnNormalSize +
                              kChecksumSize;
    if (expected != bytes.size())
        return corrupt(std::to_string(bytes.size()) + " bytes where its counts need " +
                       std::to_string(expected));
    const size_t payload = bytes.size() - kChecksumSize;
    Reader tail{bytes.data(), bytes.size(), payload};
    uint64_t checksum = 0;
    tail.u64(checksum);
    if (checksum != fnv1a(bytes.data(), payload)) return corrupt("checksum mismatch");

    if (source > uint32_t(ProxySource::AuthoredCollider))
        return corrupt("unknown source " + std::to_string(source));
    if (backend > uint32_t(ProxyBackend::None)) return corrupt("unknown backend " + std::to_string(backend));
    if (indexCount % 3 != 0) return corrupt("index count is not a multiple of 3");
    p.mesh.positions.resize(vertexCount);
    p.mesh.normals.resize(vertexCount);
    p.mesh.indices.resize(indexCount);
    for (glm::vec3& v : p.mesh.positions)
        r.f32(v.x), r.f32(v.y), r.f32(v.z);
    for (glm::vec3& v : p.mesh.normals)
        r.f32(v.x), r.f32(v.y), r.f32(v.z);
    for (uint32_t& i : p.mesh.indices)
        r.u32(i);
    std::vector<DrawnNormals::Packed> drawn(drawnCount);
    for (DrawnNormals::Packed& n : drawn)
        r.i16(n[0]), r.i16(n[1]), r.i16(n[2]);
    p.drawnNormals = DrawnNormals(std::move(drawn));
    if (!p.drawnNormals.empty() && !p.drawnNormals.fits(p.mesh.triangleCount()))
        return corrupt(std::to_string(drawnCount) + " drawn normals for " +
                       std::to_string(p.mesh.triangleCount()) + " triangles");
    for (uint32_t i : p.mesh.indices)
        if (i >= vertexCount) return corrupt("index past the vertex count");
    for (size_t i = 0; i < p.mesh.positions.size(); ++i) {
        const glm::vec3& a = p.mesh.positions[i];
        const glm::vec3& n = p.mesh.normals[i];
        if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(a.z) || !std::isfinite(n.x) ||
            !std::isfinite(n.y) || !std::isfinite(n.z))
            return corrupt("non-finite vertex data");
    }
    if (!std::isfinite(p.errorBound) || p.errorBound < 0.0) return corrupt("invalid error bound");
    p.source = ProxySource(source);
    p.backend = ProxyBackend(backend);
    p.toleranceMet = (flags & 1u) != 0;
    p.attempts = attempts;
    p.inputTriangles = size_t(inputTriangles);
    p.samples = size_t(samples);
    p.proxyTriangles = p.mesh.triangleCount();
    p.cached = true;
    return p;
}

Status storeCachedProxy(const std::string& directory, uint64_t key, const Proxy& proxy) {
    const Mesh& m = proxy.mesh;
    const std::string path = proxyCachePath(directory, key);
    if (m.normals.size() != m.positions.size())
        return fail("cache entry " + path + " not written: the proxy has no normal per position");
    const std::vector<DrawnNormals::Packed>& drawn = proxy.drawnNormals.packed();
    if (m.positions.size() > UINT32_MAX || m.indices.size() > UINT32_MAX || drawn.size() > UINT32_MAX)
        return fail("cache entry " + path + " not written: the proxy is too large");
    Writer w;
    w.bytes.reserve(kHeaderSize + m.positions.size() * 24 + m.indices.size() * 4 +
                    drawn.size() * kDrawnNormalSize + kChecksumSize);
    for (char c : kMagic)
        w.bytes.push_back((unsigned char)c);
    w.u32(kFormatVersion);
    w.u64(key);
    w.u32(uint32_t(proxy.source));
    w.u32(uint32_t(proxy.backend));
    w.u32(proxy.toleranceMet ? 1u : 0u);
    w.u32(proxy.attempts);
    w.u64(proxy.inputTriangles);
    w.u64(proxy.samples);
    w.f64(proxy.tolerance);
    w.f64(proxy.errorBound);
    w.f64(proxy.proxyToRenderMax);
    w.f64(proxy.renderToProxyMax);
    w.f64(proxy.samplingMargin);
    w.u32(uint32_t(m.positions.size()));
    w.u32(uint32_t(m.indices.size()));
    w.u32(uint32_t(drawn.size()));
    for (const glm::vec3& v : m.positions)
        w.f32(v.x), w.f32(v.y), w.f32(v.z);
    for (const glm::vec3& v : m.normals)
        w.f32(v.x), w.f32(v.y), w.f32(v.z);
    for (uint32_t i : m.indices)
        w.u32(i);
    for (const DrawnNormals::Packed& n : drawn)
        w.i16(n[0]), w.i16(n[1]), w.i16(n[2]);
    w.u64(fnv1a(w.bytes.data(), w.bytes.size()));

    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec) return fail("cache directory " + directory + " cannot be created: " + ec.message());
    static std::atomic<uint64_t> counter{0};
    const uint64_t unique = uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                            (uint64_t(std::hash<std::thread::id>()(std::this_thread::get_id())) << 1) ^
                            (counter.fetch_add(1) * 0x9e3779b97f4a7c15ULL);
    char suffix[40];
    std::snprintf(suffix, sizeof(suffix), ".tmp-%016llx", (unsigned long long)unique);
    const std::string temp = path + suffix;
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) return fail("cache entry " + temp + " cannot be created");
        out.write(reinterpret_cast<const char*>(w.bytes.data()), std::streamsize(w.bytes.size()));
        out.close();
        if (!out) {
            fs::remove(temp, ec);
            return fail("cache entry " + temp + " cannot be written");
        }
    }
    fs::rename(temp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        return fail("cache entry " + path + " cannot be renamed into place: " + ec.message());
    }
    return {};
}

} // namespace spatter
