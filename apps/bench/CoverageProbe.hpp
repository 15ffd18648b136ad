#pragma once
// CoverageProbe: decals as the renderer draws them in its coverage view (headless OpenGL), read back
// as a mask of covered pixels, and the IoU of two masks. Benchmarks place the same shots through a
// proxy and on the render mesh and compare what is drawn: an error the player could see, where the
// distance of a hit to the render surface only bounds it.

#include "spatter/core/DecalType.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace spatter::bench {

// Decal settings under which nothing is evicted: benchmarks time placement, not the limits, and a
// probe draws the decal of every shot it compares.
DecalSettings unlimited(double diagonal, uint64_t seed);

// A decal system over `world` (its error, if it failed) with unlimited(diagonal, seed) settings and
// `type` as its type 0: what a probe's decals are placed by.
Result<DecalSystem> coverageSystem(Result<CollisionWorld> world, const DecalType& type, double diagonal,
                                   uint64_t seed);

// A coverage type of `size`: no random rotation, so that a decal's frame depends on its ray only, not
// on the shots before it that one surface caught and the other missed.
DecalType coverageType(double size);

class CoverageProbe {
public:
    // A headless context and a width x height renderer of `scene`, drawing decals of `type` (the
    // decal type 0 of every system whose decals it draws), with a face normal target when
    // `faceNormals` (RendererSettings::faceNormals). Fails without an OpenGL context.
    static Result<CoverageProbe> create(const Scene& scene, int width, int height, const DecalType& type,
                                        bool faceNormals = false);

    const std::string& glRenderer() const { return context_->info().renderer; }
    const DecalType& type() const { return type_; }
    // The scene as drawn: a host poses it (setPose) and names the decal system's object IDs here.
    Renderer& renderer() { return renderer_; }

    // One byte a pixel, 1 where `decals` cover the scene seen from `camera`.
    Result<std::vector<uint8_t>> mask(const Camera& camera, const std::vector<Decal>& decals);

private:
    CoverageProbe(std::unique_ptr<GlContext> context, Renderer renderer, const DecalType& type)
        : context_(std::move(context)), renderer_(std::move(renderer)), type_(type) {}

    std::unique_ptr<GlContext> context_;
    Renderer renderer_;
    DecalType type_;
};

// Intersection over union of two masks of the same image; NaN (not measured) when neither covers a
// pixel.
double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

} // namespace spatter::bench
