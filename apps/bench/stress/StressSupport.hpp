#pragma once
// Pieces the stress cases share: scenes with known geometry, the checks every placed decal must
// pass, shared edges of meshes, the renderer of the render cases, and number formatting for failure
// messages.

#include "StressCase.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace spatter::stress {

constexpr double kPi = 3.14159265358979323846;

// A static square on the plane y = 0 spanning [-half, half] in x and z, facing +Y, cut into
// 4 x 4 squares (open).
Scene planeScene(double half);

// A decal type with the given size, largest angle and size jitter (no random rotation unless asked).
DecalType makeType(const std::string& name, float size, float maxAngleDeg, float jitter = 0.0f,
                   bool randomRotation = true);

// Decal settings with limits far above anything a case spawns, so that nothing is evicted.
DecalSettings unlimitedSettings(uint64_t seed);

// Uniform random unit vector (double).
glm::dvec3 randomUnit(Rng& rng);
// Uniform in [lo, hi) in double precision.
double uniform(Rng& rng, double lo, double hi);

// frameError, with any non-finite component counted as infinity.
double frameErrorOf(const Frame& f);
bool finite3(const glm::dvec3& v);
bool finite3(const glm::vec3& v);

// What can be wrong with a placed decal and its world box; the largest errors seen.
struct DecalCheck {
    double frameError = 0.0; // object-space frame and world frame (frameError)
    double sizeError = 0.0;  // |world size / type size - 1| beyond the type's jitter
    double depthError = 0.0; // |world half-depth / (h + margin * max(w, h)) - 1| (automatic types)
    double boxInverse = 0.0; // |box * box^-1 - I| (max norm) in double, from the float decal
    size_t nonFinite = 0;    // decals with a NaN or Inf anywhere
    size_t checked = 0;
};

// Checks one placed decal (see DecalCheck); returns a description of the worst problem when any
// error exceeds `frameBound` / `relBound` (empty otherwise).
std::string checkDecal(const DecalSystem& sys, const Decal& d, const DecalType& type, DecalCheck& check,
                       double frameBound, double relBound);

// An edge of a mesh shared by exactly two triangles of non-zero area, with the two face normals
// (object space, unit).
struct SharedEdge {
    uint32_t a = 0, b = 0;
    glm::dvec3 n0{0.0}, n1{0.0};
};
std::vector<SharedEdge> sharedEdges(const Mesh& mesh);

// A vertex whose every incident edge is a shared edge, with the normals of its triangles.
struct InteriorVertex {
    uint32_t v = 0;
    std::vector<glm::dvec3> normals;
};
std::vector<InteriorVertex> interiorVertices(const Mesh& mesh);

// True when every edge is used exactly twice, once in each direction.
bool closedMesh(const Mesh& mesh);

// A width x height renderer on cfg's headless context for a render case. Fails when there is none:
// without a context `r` is marked skipped (saying why); when the renderer cannot be created `r`
// records the failure and an infinite "renderer" row. On failure the case returns `r` as it is.
// `gpuCullingFrom` as RendererSettings' (0: the projector culls on the GPU).
Result<Renderer> caseRenderer(const StressConfig& cfg, int width, int height, StressResult& r,
                              std::optional<size_t> gpuCullingFrom = std::nullopt);

// "%.6g" and "(x, y, z)" with 17 digits.
std::string num(double v);
std::string vec(const glm::dvec3& v);

} // namespace spatter::stress
