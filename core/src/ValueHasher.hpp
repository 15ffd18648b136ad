#pragma once
// Internal to core: an incremental FNV-1a hash over values written little-endian, so that a cache
// key is the same on every machine (ProxyCache.cpp, DeformingProxy.cpp).

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyCache.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <vector>

namespace spatter::detail {

inline uint32_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

inline uint64_t doubleBits(double d) {
    uint64_t u;
    std::memcpy(&u, &d, 8);
    return u;
}

struct ValueHasher {
    uint64_t h = kFnvOffset;

    void u32(uint32_t v) {
        unsigned char b[4];
        for (int i = 0; i < 4; ++i)
            b[i] = (unsigned char)(v >> (8 * i));
        h = fnv1a(b, 4, h);
    }
    void u64(uint64_t v) {
        unsigned char b[8];
        for (int i = 0; i < 8; ++i)
            b[i] = (unsigned char)(v >> (8 * i));
        h = fnv1a(b, 8, h);
    }
    void f32(float v) { u32(floatBits(v)); }
    void f64(double v) { u64(doubleBits(v)); }
    void vec3(const glm::vec3& v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }
    void mat4(const glm::dmat4& m) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                f64(m[c][r]);
    }
    // A vector's size, then each element through `add`.
    template <class T, class Add> void each(const std::vector<T>& v, Add add) {
        u64(v.size());
        for (const T& x : v)
            add(x);
    }
    void mesh(const Mesh& m) {
        each(m.positions, [&](const glm::vec3& p) { vec3(p); });
        each(m.indices, [&](uint32_t i) { u32(i); });
    }
};

} // namespace spatter::detail
