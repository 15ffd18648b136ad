#include "BenchSupport.hpp"

#include "LoopSubdivision.hpp"

#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "cli/Arguments.hpp"
#include "cli/Numbers.hpp"
#include "cli/OutputCleanup.hpp"
#include "cli/PathChecks.hpp"
#include "spatter/core/TextFields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace spatter::bench {

namespace fs = std::filesystem;

// ---- Command line ----------------------------------------------------------------------------

std::string Args::value(const std::string& name, const std::string& fallback) const {
    auto it = values.find(name);
    return it == values.end() ? fallback : it->second;
}

Result<Args> parseArgs(int argc, char** argv, const std::set<std::string>& valued,
                       const std::set<std::string>& switches) {
    Args args;
    cli::Arguments walk(argc, argv);
    while (walk.more()) {
        const Result<std::string> a = walk.next();
        if (!a) return fail(a.error());
        if (switches.count(*a)) {
            args.flags.insert(*a);
        } else if (a->size() > 2 && a->compare(0, 2, "--") == 0) {
            if (!valued.count(*a)) return fail("unknown option " + *a);
            const std::optional<std::string> v = walk.value();
            if (!v) return fail(*a + " needs a value");
            args.values[*a] = *v;
        } else {
            args.positional.push_back(*a);
        }
    }
    if (args.values.count("--json"))
        if (Status s = cli::creatableFile({"--json", args.values["--json"]}); !s) return fail(s.error());
    return args;
}

Result<double> parseNumber(const std::string& text, const std::string& option) {
    double v = 0.0;
    if (!parseDecimal(text, v)) return fail(option + ": '" + text + "' is not a finite decimal number");
    return v;
}

Result<uint64_t> parseCount(const std::string& text, const std::string& option) {
    uint64_t v = 0;
    if (!cli::parseWhole(text, INT64_MAX, v)) return fail(option + ": '" + text + "' is not a count");
    return v;
}

Status checkFilter(const std::string& text, const std::string& option) {
    const std::string pattern = !text.empty() && text[0] == '-' ? text.substr(1) : text; // '-': all but
    try {
        const std::regex compiled(pattern, std::regex::extended);
    } catch (const std::regex_error& e) {
        return fail(option + ": '" + text + "' is not a regular expression (" + e.what() + ")");
    }
    return {};
}

Result<std::vector<double>> parseNumberList(const std::string& text, const std::string& option) {
    std::vector<double> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        Result<double> v = parseNumber(item, option);
        if (!v) return fail(v.error());
        out.push_back(v.value());
    }
    if (out.empty()) return fail(option + ": empty list");
    return out;
}

int usageError(const std::string& command, const std::string& message) {
    std::cerr << "spatter-bench " << command << ": " << message << "\n(see spatter-bench " << command
              << " --help)\n";
    return 2;
}

std::optional<Args> commandArgs(int argc, char** argv, const std::string& command, const std::string& usage,
                                const std::set<std::string>& valued, std::set<std::string> switches,
                                int& exitCode) {
    switches.insert({"--help", "-h"});
    Result<Args> parsed = parseArgs(argc, argv, valued, switches);
    if (!parsed) {
        exitCode = usageError(command, parsed.error());
        return std::nullopt;
    }
    if (parsed->has("--help") || parsed->has("-h")) {
        std::cout << usage;
        exitCode = 0;
        return std::nullopt;
    }
    return std::move(parsed).value();
}

// ---- Statistics ------------------------------------------------------------------------------

double threadCpuNow() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * double(values.size()));
    const size_t index = rank < 1.0 ? 0 : size_t(rank) - 1;
    return values[std::min(index, values.size() - 1)];
}

double median(std::vector<double> values) {
    return percentile(std::move(values), 0.5);
}

// ---- The machine -----------------------------------------------------------------------------

MachineInfo machineInfo() {
    MachineInfo m;
    m.threads = std::max(1u, std::thread::hardware_concurrency());
    std::ifstream cpu("/proc/cpuinfo");
    for (std::string line; std::getline(cpu, line);) {
        if (line.compare(0, 10, "model name") != 0) continue;
        const size_t colon = line.find(':');
        if (colon != std::string::npos) m.cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
        break;
    }
    if (m.cpu.empty()) m.cpu = "unknown CPU";
    std::ifstream load("/proc/loadavg");
    std::string a, b, c;
    if (load >> a >> b >> c) m.loadavg = a + " " + b + " " + c;
    return m;
}

Json toJson(const MachineInfo& m) {
    Json j;
    j["cpu"] = m.cpu;
    j["threads"] = m.threads;
    j["loadavg"] = m.loadavg;
    return j;
}

std::string describe(const MachineInfo& m) {
    return m.cpu + " (" + std::to_string(m.threads) + " threads), load " + m.loadavg;
}

// ---- Input meshes ----------------------------------------------------------------------------

std::string sharedDataDir() {
    if (const char* env = std::getenv("SPATTER_SHARED_DATA"); env && *env) return env;
    std::error_code ec;
    if (fs::is_directory(SPATTER_BENCH_SHARED_DATA, ec))
        return fs::path(SPATTER_BENCH_SHARED_DATA).lexically_normal().string();
    return "";
}

std::string resolveInput(const std::string& spec) {
    if (spec.compare(0, 8, "builtin:") == 0) return spec;
    std::error_code ec;
    if (fs::is_regular_file(spec, ec)) return spec;
    const std::string data = sharedDataDir();
    if (data.empty()) return "";
    for (const fs::path& p : {fs::path(data) / spec, fs::path(data) / "meshes" / spec})
        if (fs::is_regular_file(p, ec)) return p.string();
    return "";
}

Mesh mergeReceivers(const Scene& scene) {
    Mesh out;
    for (const SceneObject& o : scene.objects) {
        if (!o.receivesDecals) continue;
        const uint32_t base = uint32_t(out.positions.size());
        for (const glm::vec3& p : o.mesh->positions)
            out.positions.push_back(glm::vec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
        const bool mirrored = glm::determinant(glm::dmat3(o.transform)) < 0.0;
        for (size_t t = 0; t + 2 < o.mesh->indices.size(); t += 3) {
            const uint32_t a = o.mesh->indices[t], b = o.mesh->indices[t + 1], c = o.mesh->indices[t + 2];
            out.indices.insert(out.indices.end(),
                               {base + a, base + (mirrored ? c : b), base + (mirrored ? b : c)});
        }
    }
    computeNormals(out);
    return out;
}

double referencedDiagonal(const Mesh& mesh) {
    Bounds b;
    for (uint32_t i : mesh.indices)
        if (i < mesh.positions.size()) b.extend(mesh.positions[i]);
    return double(b.diagonal());
}

Result<InputMesh> loadInputMesh(const std::string& spec, int loopSteps) {
    const std::string path = resolveInput(spec);
    if (path.empty())
        return fail("'" + spec + "' is neither a builtin scene nor a file (nor one in the shared data '" +
                    sharedDataDir() + "')");
    Result<Scene> scene = loadScene(path);
    if (!scene) return fail(scene.error());
    InputMesh in;
    in.source = spec; // as given: reports name what was asked for, not where this machine keeps it
    in.name = path.compare(0, 8, "builtin:") == 0 ? path.substr(8) : fs::path(path).stem().string();
    in.mesh = mergeReceivers(scene.value());
    if (in.mesh.triangleCount() == 0) return fail("'" + path + "' has no triangles that receive decals");
    if (loopSteps > 0) {
        Result<Mesh> sub = loopSubdivide(in.mesh, loopSteps, in.droppedFaces);
        if (!sub) return fail("'" + path + "': " + sub.error());
        in.mesh = std::move(sub).value();
        in.name += "-loop" + std::to_string(loopSteps);
    }
    in.diagonal = referencedDiagonal(in.mesh);
    if (!(in.diagonal > 0.0)) return fail("'" + path + "' has no extent");
    return in;
}

Scene singleObjectScene(const Mesh& mesh, const std::string& name) {
    Scene scene;
    scene.source = name;
    SceneObject o;
    o.name = name;
    o.mesh = shareMesh(mesh);
    scene.objects.push_back(std::move(o));
    return scene;
}

// ---- Rays ------------------------------------------------------------------------------------

SurfaceSampler::SurfaceSampler(const Mesh& mesh) : mesh_(mesh) {
    cumulative_.reserve(mesh.triangleCount());
    double total = 0.0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        total += 0.5 * glm::length(glm::cross(b - a, c - a));
        cumulative_.push_back(total);
    }
}

glm::dvec3 SurfaceSampler::sample(float u, float v, float w) const {
    const double target = double(u) * cumulative_.back();
    size_t t = size_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), target) - cumulative_.begin());
    t = std::min(t, cumulative_.size() - 1);
    double a = double(v), b = double(w);
    if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    const glm::dvec3 p0(mesh_.positions[mesh_.indices[3 * t]]), p1(mesh_.positions[mesh_.indices[3 * t + 1]]),
        p2(mesh_.positions[mesh_.indices[3 * t + 2]]);
    return p0 + a * (p1 - p0) + b * (p2 - p0);
}

namespace {

glm::dvec3 randomUnit(Rng& rng) {
    const double z = 2.0 * double(rng.uniform()) - 1.0;
    const double phi = 2.0 * kPi * double(rng.uniform());
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Unit vectors completing `d` to an orthonormal basis.
void basis(const glm::dvec3& d, glm::dvec3& a, glm::dvec3& b) {
    const glm::dvec3 helper = std::fabs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    a = glm::normalize(glm::cross(d, helper));
    b = glm::cross(d, a);
}

} // namespace

std::vector<Ray> scatteredRays(const Mesh& mesh, size_t count, uint64_t seed) {
    std::vector<Ray> rays;
    const SurfaceSampler surface(mesh);
    const Bounds b = mesh.bounds();
    if (surface.empty()) return rays;
    const glm::dvec3 centre = glm::dvec3(b.center());
    const double radius = 0.75 * double(b.diagonal());
    Rng rng(seed);
    rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        Ray r;
        r.origin = centre + randomUnit(rng) * radius;
        glm::dvec3 target;
        if (rng.below(10) != 0) {
            const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
            target = surface.sample(u, v, w);
        } else {
            const double x = rng.uniform(), y = rng.uniform(), z = rng.uniform();
            target = glm::dvec3(b.min) + glm::dvec3(x, y, z) * glm::dvec3(b.max - b.min);
        }
        r.direction = target - r.origin;
        rays.push_back(r);
    }
    return rays;
}

std::vector<Ray> shotgunRays(const Mesh& mesh, size_t batches, size_t raysPerBatch, double coneDeg,
                             uint64_t seed) {
    std::vector<Ray> rays;
    const SurfaceSampler surface(mesh);
    const Bounds b = mesh.bounds();
    if (surface.empty()) return rays;
    const glm::dvec3 centre = glm::dvec3(b.center());
    const double radius = 0.75 * double(b.diagonal());
    Rng rng(seed);
    rays.reserve(batches * raysPerBatch);
    for (size_t k = 0; k < batches; ++k) {
        const glm::dvec3 origin = centre + randomUnit(rng) * radius;
        const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
        const glm::dvec3 aim = glm::normalize(surface.sample(u, v, w) - origin);
        for (size_t i = 0; i < raysPerBatch; ++i) {
            Ray r;
            r.origin = origin;
            r.direction = randomConeDirection(aim, 0.5 * coneDeg * kPi / 180.0, rng);
            rays.push_back(r);
        }
    }
    return rays;
}

glm::dvec3 randomConeDirection(const glm::dvec3& axis, double halfAngle, Rng& rng) {
    glm::dvec3 ax, ay;
    basis(axis, ax, ay);
    // Uniform over the spherical cap: cos(theta) uniform in [cos(half angle), 1].
    const double c = 1.0 - double(rng.uniform()) * (1.0 - std::cos(halfAngle));
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = 2.0 * kPi * double(rng.uniform());
    return axis * c + (ax * std::cos(phi) + ay * std::sin(phi)) * s;
}

Status writeRays(const std::vector<Ray>& rays, const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return fail("cannot write '" + path + "'");
    for (const Ray& r : rays)
        std::fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g\n", r.origin.x, r.origin.y, r.origin.z,
                     r.direction.x, r.direction.y, r.direction.z);
    const bool ok = std::fclose(f) == 0;
    return ok ? Status() : Status(fail("cannot write '" + path + "'"));
}

// ---- Output ----------------------------------------------------------------------------------

namespace {

bool numeric(const std::string& s) {
    if (s.empty() || s == "-") return true;
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return end != s.c_str() && (*end == '\0' || *end == 'x' || *end == '%');
}

} // namespace

void printTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
    std::vector<size_t> width(header.size());
    for (size_t c = 0; c < header.size(); ++c)
        width[c] = header[c].size();
    for (const auto& row : rows)
        for (size_t c = 0; c < row.size() && c < width.size(); ++c)
            width[c] = std::max(width[c], row[c].size());
    auto line = [&](const std::vector<std::string>& cells, bool head) {
        std::string out;
        for (size_t c = 0; c < width.size(); ++c) {
            const std::string cell = c < cells.size() ? cells[c] : "";
            const std::string pad(width[c] - std::min(width[c], cell.size()), ' ');
            const bool right = !head && c > 0 && numeric(cell);
            out += (c ? "  " : "") + (right ? pad + cell : cell + pad);
        }
        while (!out.empty() && out.back() == ' ')
            out.pop_back();
        std::printf("%s\n", out.c_str());
    };
    line(header, true);
    for (const auto& row : rows)
        line(row, false);
    std::fflush(stdout);
}

std::string fmt(double v, int digits) {
    if (std::isnan(v)) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string fixed(double v, int decimals) {
    if (std::isnan(v)) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

Json number(double v) {
    if (std::isfinite(v)) return v;
    return nullptr;
}

Status writeJson(const Json& j, const std::string& path) {
    cli::OutputCleanup cleanup; // a file half written
    cleanup.writing(path);
    std::ofstream out(path, std::ios::binary);
    if (!out) return fail("cannot write '" + path + "'");
    out << j.dump(2) << "\n";
    out.close();
    if (!out) return fail("cannot write '" + path + "'");
    cleanup.keep();
    return {};
}

ScratchDirectory::ScratchDirectory(const std::string& name) {
    std::error_code ec;
    const fs::path dir =
        fs::temp_directory_path(ec) / ("spatter-bench-" + std::to_string(getpid()) + "-" + name);
    path_ = dir.string();
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    if (ec) error_ = "cannot create " + path_ + ": " + ec.message();
}

ScratchDirectory::~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

} // namespace spatter::bench
