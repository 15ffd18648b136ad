#include "CoverageProbe.hpp"

#include <limits>

namespace spatter::bench {

DecalSettings unlimited(double diagonal, uint64_t seed) {
    DecalSettings s;
    s.seed = seed;
    s.cellSize = float(diagonal / 40.0);
    s.maxPerCell = 1u << 30;
    s.maxPerObject = 1u << 30;
    s.budget = 1u << 30;
    return s;
}

Result<DecalSystem> coverageSystem(Result<CollisionWorld> world, const DecalType& type, double diagonal,
                                   uint64_t seed) {
    if (!world) return fail(world.error());
    Result<DecalSystem> system = DecalSystem::create(std::move(world).value(), unlimited(diagonal, seed));
    if (!system) return system;
    if (Result<uint16_t> t = system->registerType(type); !t) return fail(t.error());
    return system;
}

DecalType coverageType(double size) {
    DecalType t;
    t.name = "coverage";
    t.size = glm::vec2(float(size));
    t.randomRotation = false;
    return t;
}

Result<CoverageProbe> CoverageProbe::create(const Scene& scene, int width, int height, const DecalType& type,
                                            bool faceNormals) {
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) return fail(gl.error());
    auto context = std::make_unique<GlContext>(std::move(gl).value());
    RendererSettings rs;
    rs.width = width;
    rs.height = height;
    rs.faceNormals = faceNormals;
    Result<Renderer> renderer = Renderer::create(*context, rs);
    if (!renderer) return fail(renderer.error());
    if (Status s = renderer->setScene(scene); !s) return fail(s.error());
    CoverageProbe p(std::move(context), std::move(renderer).value(), type);
    p.renderer_.setDecalTypes({type});
    return p;
}

Result<std::vector<uint8_t>> CoverageProbe::mask(const Camera& camera, const std::vector<Decal>& decals) {
    renderer_.setDecals(decals);
    Result<FrameStats> stats = renderer_.render(camera, View::Coverage);
    if (!stats) return fail(stats.error());
    Result<Image> image = renderer_.readback();
    if (!image) return fail(image.error());
    std::vector<uint8_t> m(size_t(image->width) * size_t(image->height));
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = image->rgba[4 * i] > 127 ? 1 : 0;
    return m;
}

double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t both = 0, either = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
        both += a[i] & b[i];
        either += a[i] | b[i];
    }
    return either ? double(both) / double(either) : std::numeric_limits<double>::quiet_NaN(); // nothing seen
}

} // namespace spatter::bench
