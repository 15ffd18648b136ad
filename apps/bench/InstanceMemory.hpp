#pragma once
// spatter-bench memory's rows for a mesh placed many times: what the scene, the proxy list and the
// collision world keep for the objects, each object sharing the one mesh and proxy against each given
// a copy of its own (as a scene held them before objects shared their meshes), measured in one run.

#include "BenchSupport.hpp"

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"

#include <cstddef>

namespace spatter::bench {

// Prints the rows for `copies` static objects of `mesh` (a row apart each) with `proxy`, and returns
// them: {"copies", "scene_shared_bytes", "scene_copied_bytes", "proxies_shared_bytes",
// "proxies_copied_bytes", "world_bytes"} (C heap).
Json instanceMemory(const Mesh& mesh, const Proxy& proxy, size_t copies);

} // namespace spatter::bench
