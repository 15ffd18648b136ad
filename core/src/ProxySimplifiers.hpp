#pragma once
// Internal to core: the simplifiers the proxy search runs (ProxySearch.cpp), each giving a mesh of the
// referenced vertices only, which the builder then welds, splits at creases and certifies.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <cstdint>

namespace spatter::detail {

// meshoptimizer. `tolerance` is absolute (infinity: stop at the budget only); `budget` 0 is no limit.
// `resultError` receives the error meshoptimizer reports for the result (absolute).
Mesh simplifyMeshopt(const Mesh& input, double tolerance, uint32_t budget, bool lockBorder,
                     double& resultError);

// meshoptimizer's sloppy simplifier: ignores topology, so it can reach budgets the others cannot.
Mesh simplifySloppy(const Mesh& input, uint32_t budget);

// OpenMesh Decimater. `tolerance` absolute (infinity: no Hausdorff constraint); `budget` 0 is no limit.
// Faces that would make the mesh non-manifold are added on their own copies of their vertices
// (`detachedFaces` counts them); boundaries and sharp features are kept as `s` asks. Fails when the
// decimater cannot start or `progress` cancels.
Result<Mesh> simplifyOpenMesh(const Mesh& input, double tolerance, uint32_t budget, const ProxySettings& s,
                              const ProgressCallback& progress, size_t& detachedFaces);

} // namespace spatter::detail
