#pragma once
// The three.js peer (bench/peers/threejs): the same mesh and rays through three-mesh-bvh's raycast and
// three.js's DecalGeometry, run with Node when node and npm are available.

#include "BenchSupport.hpp"

#include <string>

namespace spatter::bench {

struct PeerRun {
    bool ran = false;
    std::string skipped; // why it did not run (node or npm missing, install failed, ...)
    Json result;         // what decals.mjs printed: per_decal_ns, raycast_ns, decal_geometry_ns, ...
};

// Writes nothing itself: `objPath` and `raysPath` are the files the peer reads (writeObj, writeRays).
// Installs the peer's packages with `npm ci` into its node_modules when they are missing, then runs
// decals.mjs for at most about `maxSeconds` of decal building. `peerDir` empty means the directory
// of the source tree (bench/peers/threejs).
PeerRun runThreejsPeer(const std::string& objPath, const std::string& raysPath, double decalSize,
                       double maxSeconds, uint64_t seed, const std::string& workDir,
                       const std::string& peerDir = "");

} // namespace spatter::bench
