#include "StressCase.hpp"

#include <chrono>
#include <cmath>

namespace spatter::stress {

namespace {
constexpr size_t kMaxFailures = 12;
} // namespace

bool StressResult::pass() const {
    for (const StressRow& r : rows)
        if (!r.pass()) return false;
    return true;
}

StressRow& StressResult::row(const std::string& metric, double worst, double bound, size_t samples,
                             const std::string& note) {
    StressRow r;
    r.metric = metric;
    r.worst = worst;
    r.bound = bound;
    r.samples = samples;
    r.note = note;
    rows.push_back(r);
    return rows.back();
}

void StressResult::failure(const std::string& what) {
    if (failures.size() < kMaxFailures) failures.push_back(what);
}

double worse(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return NAN;
    return a > b ? a : b;
}

const std::vector<StressCase>& stressCases() {
    static const std::vector<StressCase> cases = {
        {"frames", "tangent frames: a million random normals, the axes, normals 1e-9..1e-3 from the poles",
         runFrames},
        {"grazing", "rays 80..89.999 degrees from the normal on a plane and a box", runGrazing},
        {"watertight", "rays aimed exactly at shared edges and vertices of closed meshes", runWatertight},
        {"degenerate", "zero-area triangles, slivers, duplicate and unreferenced vertices", runDegenerate},
        {"far-placement", "decal centres with the scene translated by 1e3..1e6 (API)", runFarPlacement},
        {"far-tool", "decal centres with spatter-place --translate 1e3..1e6", runFarTool},
        {"far-render", "coverage with the scene translated by 1e3..1e6 (renderer)", runFarRender},
        {"extreme-sizes", "decals 1e-4..1e4 times the scene scale: transforms and boxes", runExtremeSizes},
        {"extreme-sizes-render", "rendered coverage of decals 1e-4..1e4 times the scene scale",
         runExtremeSizesRender},
        {"depth", "positions rebuilt from reversed-Z float depth at 0.1 m..10 km, against standard Z",
         runDepth},
        {"nonfinite-placement", "NaN, Inf and denormal input to the placement API", runNonFinitePlacement},
        {"nonfinite-render", "NaN, Inf and denormal input to the renderer and the camera",
         runNonFiniteRender},
        {"soak", "spawns far past the budget (10 million at full size) through the renderer's change list",
         runSoak},
    };
    return cases;
}

StressResult runCase(const StressCase& c, const StressConfig& config) {
    const auto start = std::chrono::steady_clock::now();
    StressResult r = c.run(config);
    r.name = c.name;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

} // namespace spatter::stress
