#pragma once
// Internal to core: the meshes around a simplifier run (ProxySearch.cpp, ProxyBuilder.cpp): the render
// mesh welded for its input, and a run's result made a proxy.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"

#include <cstddef>

namespace spatter::detail {

// Triangles of `m` with three distinct indices and non-zero area.
size_t surfaceTriangleCount(const Mesh& m);

// Positions and indices only: vertices with bit-identical positions merged, triangles with a repeated
// index or zero area dropped, unreferenced vertices removed.
Mesh weldedSurface(const Mesh& in);

// Gives each vertex one copy per fan of triangles joined across edges whose dihedral angle is at most
// `angleDegrees`; edges used by other than two triangles separate fans too. Afterwards vertices along
// sharp edges are split, which keeps normals crisp there and makes meshoptimizer treat the edges as
// seams (collapsible only along themselves).
void splitCreases(Mesh& m, float angleDegrees);

// What meshoptimizer simplifies: a welded mesh (the render mesh or a run of the search) with its
// creases split where `s` keeps sharp features.
Mesh meshoptInputOf(Mesh welded, const ProxySettings& s);

// A run of the search, welded (weldedSurface), made into a proxy: creases split (so that normals stay
// crisp along sharp edges), normals computed.
Mesh finishProxy(Mesh welded, const ProxySettings& s);

} // namespace spatter::detail
