#pragma once
// UvOverlap: checks that a mesh's UV layout maps every triangle to its own part of the unit square,
// which texture-space decals need (a decal splatted into a texel shows on every triangle that maps
// onto it). Triangles that share an edge or a vertex in UV space touch without overlapping.

#include "spatter/core/Mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace spatter {

struct UvOverlapReport {
    size_t triangles = 0;        // triangles examined
    size_t overlappingPairs = 0; // pairs of triangles whose UV interiors overlap
    size_t outOfRange = 0;       // triangles with a UV outside [0, 1]^2 (they would wrap)
    size_t degenerate = 0;       // triangles with (near) zero UV area: they get no texels
    // The first overlapping pairs found (at most the maxPairs given to findUvOverlaps).
    std::vector<std::pair<uint32_t, uint32_t>> pairs;

    // True when the layout can carry texture-space decals: no overlap and nothing out of range.
    bool usable() const { return overlappingPairs == 0 && outOfRange == 0; }
    // One line, e.g. "3 overlapping triangle pairs (first: 4 and 17), 0 out of [0, 1], 1 degenerate".
    std::string summary() const;
};

// Examines the UVs of `mesh`. A pair overlaps when no edge direction of either triangle separates
// them by more than `tolerance` (UV units), so neighbours across a shared edge do not count.
// A mesh without UVs, or one that fails validateMesh, is reported as an error (no triangle can be
// checked). Cost: a uniform grid over the unit square, about O(n) for well-spread layouts.
Result<UvOverlapReport> findUvOverlaps(const Mesh& mesh, size_t maxPairs = 16, float tolerance = 1e-6f);

// Maps the UVs of `mesh` affinely into [margin, 1 - margin]^2, keeping their aspect ratio, so that a
// layout in metres (the MeshBuilder convention) becomes one that a texture-space decal texture can
// hold when its charts do not overlap. Does nothing for a mesh without UVs or with non-finite ones;
// margin is clamped to [0, 0.25].
void fitUvsToUnitSquare(Mesh& mesh, float margin = 0.01f);

} // namespace spatter
