#pragma once
// ProxyCache: proxies stored on disk, one file per proxy, keyed by a 64-bit content hash.
//
// File `<directory>/proxy-<key as 16 hex digits>.bin`, little-endian:
//   magic "SPXC", format version (u32), key (u64),
//   source, backend, flags (u32 each; flag 1 = tolerance met), attempts (u32),
//   input triangles, samples (u64 each),
//   tolerance, error bound, proxy-to-render max, render-to-proxy max, sampling margin (f64 each),
//   vertex count, index count, drawn normal count (u32 each; the last 0, or 9 per triangle),
//   positions, normals (3 f32 per vertex each), indices (u32 each), drawn normals (3 i16 each),
//   checksum (u64): FNV-1a of every byte before it.
// An entry is written to a temporary file in the same directory and renamed over the final name, so
// a reader never sees a half-written entry. A truncated, resized or altered entry fails the size or
// checksum test and is reported as corrupt; loading never reads out of bounds.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace spatter {

// FNV-1a (64-bit) of `size` bytes, continuing from `hash` (start with kFnvOffset).
constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
uint64_t fnv1a(const void* data, size_t size, uint64_t hash = kFnvOffset);

// The key of the proxy of `render` built with `settings` (every field but cacheDirectory) and
// `authoredCollider` (nullptr for none): a hash of the positions and indices of both meshes, the
// settings and the builder's version. Normals, UVs and submeshes do not change the key.
uint64_t proxyCacheKey(const Mesh& render, const ProxySettings& settings, const Mesh* authoredCollider);

// The entry's path: `directory`/proxy-<key>.bin.
std::string proxyCachePath(const std::string& directory, uint64_t key);

// Loads the entry for `key`. Fails when there is none ("no cache entry"), or when it is corrupt: the
// message names the file and says what is wrong. The result has cached = true, seconds = 0 and no
// notes.
Result<Proxy> loadCachedProxy(const std::string& directory, uint64_t key);

// Writes the entry for `key` atomically, creating `directory` when missing. The proxy's mesh must have
// one normal per position. Fails with a message naming the file when it cannot be written.
Status storeCachedProxy(const std::string& directory, uint64_t key, const Proxy& proxy);

} // namespace spatter
