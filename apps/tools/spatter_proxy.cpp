// spatter-proxy build MESH --tolerance T[%] ...: builds the collision proxy of a mesh or scene, writes it
// as OBJ and reports its certified error bound.

#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/Threads.hpp"

#include "cli/Arguments.hpp"
#include "cli/DistinctFiles.hpp"
#include "cli/Numbers.hpp"
#include "cli/OutputCleanup.hpp"
#include "cli/PathChecks.hpp"
#include "cli/Tolerance.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <unistd.h>

static_assert(spatter::kMaxThreads == 16, "kUsage names the most threads a build uses");
static const char* kUsage =
    R"(usage: spatter-proxy build MESH --tolerance T[%] [--backend openmesh|meshopt|auto]
                           --out PROXY.obj [--report REPORT.json] [--cache DIR]
                           [--max-triangles N] [--threads N] [--quiet]

Builds the collision proxy of MESH and writes it to PROXY.obj (positions, normals, triangles).

  MESH              builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file. The render
                    meshes of all its objects are merged into one mesh in world space.
  --tolerance T     target for the error bound h, in world units, from 0 to 3.4e38; T% is a
                    percentage of the diagonal of the merged mesh's bounding box (0.5% = 0.005 x
                    diagonal).
  --backend B       openmesh (OpenMesh Decimater), meshopt (meshoptimizer, the fast path) or
                    auto (the default: meshoptimizer, fast enough for the search's runs).
  --report FILE     writes {"input_triangles", "proxy_triangles", "backend", "tolerance",
                    "error_bound", "proxy_to_render_max", "render_to_proxy_max", "seconds",
                    "cached"}: tolerance and distances in world units, backend "none" when the
                    mesh is its own proxy (a tolerance of 0, below 512 triangles within the
                    budget, or nothing to remove).
  --cache DIR       reuses or stores the proxy in DIR, keyed by a hash of the mesh and the
                    settings; DIR is a directory, or one that can be created. Without it nothing
                    is cached.
  --max-triangles N largest number of proxy triangles (0, the default: no limit).
  --threads N       threads the build uses, 1 to 16 (0, the default: the machine's, at most 16).
                    The proxy does not depend on it.
  --quiet           no progress, notes or summary on stderr (warnings still).

h is never below the true two-sided Hausdorff distance between the proxy and the merged mesh.
Numbers are decimal ("0.5", "1e-3"; no hexadecimal, no blanks; N a whole number). Each option is
given at most once, with its value (a following "--..." is not one). The files named are checked
before the work: --out and --report must be files that can be written, neither MESH nor each other.
Progress and notes go to stderr. Exit code 0 on success, 1 on an error (one line on stderr),
2 on bad usage (the checks above included). A run that fails leaves no --out or --report file of its
own: one it began is removed.
)";

namespace {

int usageError(const std::string& message) {
    std::cerr << "spatter-proxy: " << message << "\n(spatter-proxy --help for usage)\n";
    return 2;
}

// The render meshes of every object, transformed to world space, as one mesh.
spatter::Mesh mergeWorld(const spatter::Scene& scene) {
    spatter::Mesh out;
    for (const spatter::SceneObject& o : scene.objects) {
        const uint32_t base = uint32_t(out.positions.size());
        for (const glm::vec3& p : o.mesh->positions)
            out.positions.push_back(glm::vec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
        for (uint32_t i : o.mesh->indices)
            out.indices.push_back(base + i);
    }
    spatter::computeNormals(out);
    return out;
}

// The comment line of the proxy's OBJ file.
std::string objComment(const spatter::Proxy& proxy) {
    char line[256];
    std::snprintf(
        line, sizeof line, "spatter-proxy: %zu vertices, %zu triangles, source %s, backend %s, h = %.9g",
        proxy.mesh.positions.size(), proxy.mesh.triangleCount(), spatter::proxySourceName(proxy.source),
        spatter::proxyBackendName(proxy.backend), proxy.errorBound);
    return line;
}

// Progress of the whole build on stderr: on a terminal one line, rewritten in place with the stage
// at work; otherwise a line at every quarter.
class ProgressPrinter {
public:
    bool operator()(float fraction, const char* stage) {
        const int percent = int(std::lround(std::clamp(fraction, 0.0f, 1.0f) * 100.0f));
        if (tty_ && (percent != percent_ || stage_ != stage)) {
            std::fprintf(stderr, "\rspatter-proxy: %3d%% (%s)\033[K", percent, stage);
            printed_ = true;
        } else if (!tty_ && percent / 25 != percent_ / 25) {
            std::fprintf(stderr, "spatter-proxy: %3d%%\n", percent);
        }
        stage_ = stage;
        percent_ = percent;
        return true;
    }
    void finish() {
        if (printed_) std::fputc('\n', stderr);
        printed_ = false;
    }

private:
    bool tty_ = isatty(fileno(stderr)) != 0;
    bool printed_ = false;
    std::string stage_;
    int percent_ = -1;
};

// The command line after "build MESH".
struct Options {
    std::string mesh, out, report;
    bool toleranceGiven = false, quiet = false;
    spatter::ProxySettings settings;
};

// Reads the value `v` of the option `arg` into `o`; an error message, or "" when it is one.
std::string parseValue(const std::string& arg, const std::string& v, Options& o) {
    uint64_t n = 0;
    if (arg == "--tolerance") {
        o.toleranceGiven = true;
        if (!spatter::cli::parseTolerance(v, o.settings))
            return "--tolerance needs a number from 0 to 3.4e38, optionally followed by %, not '" + v + "'";
    } else if (arg == "--backend") {
        if (v == "openmesh")
            o.settings.backend = spatter::ProxyBackend::OpenMesh;
        else if (v == "meshopt")
            o.settings.backend = spatter::ProxyBackend::MeshOpt;
        else if (v == "auto")
            o.settings.backend = spatter::ProxyBackend::Auto;
        else
            return "unknown backend '" + v + "' (openmesh, meshopt or auto)";
    } else if (arg == "--out" || arg == "--report") {
        if (v.empty()) return arg + " needs a file";
        (arg == "--out" ? o.out : o.report) = v;
    } else if (arg == "--cache") {
        if (v.empty()) return "--cache needs a directory";
        o.settings.cacheDirectory = v;
    } else if (arg == "--max-triangles") {
        if (!spatter::cli::parseWhole(v, UINT32_MAX, n)) return "--max-triangles needs a whole number >= 0";
        o.settings.maxTriangles = uint32_t(n);
    } else if (arg == "--threads") {
        if (!spatter::cli::parseWhole(v, spatter::kMaxThreads, n))
            return "--threads needs a whole number from 0 to " + std::to_string(spatter::kMaxThreads);
        o.settings.threads = unsigned(n);
    }
    return "";
}

// Reads argv[3..argc) into `o`. Returns -1 to go on, or 2 after a usage error.
int parseOptions(int argc, char** argv, Options& o) {
    static const std::set<std::string> kValued = {"--tolerance", "--backend",       "--out",    "--report",
                                                  "--cache",     "--max-triangles", "--threads"};
    o.mesh = argv[2];
    spatter::cli::Arguments args(argc, argv, 3);
    while (args.more()) {
        const spatter::Result<std::string> arg = args.next();
        if (!arg) return usageError(arg.error());
        if (*arg == "--quiet") {
            o.quiet = true;
            continue;
        }
        if (!kValued.count(*arg)) return usageError("unknown argument '" + *arg + "'");
        const std::optional<std::string> v = args.value();
        if (!v) return usageError(*arg + " needs a value");
        if (const std::string error = parseValue(*arg, *v, o); !error.empty()) return usageError(error);
    }
    if (!o.toleranceGiven) return usageError("--tolerance is required");
    if (o.out.empty()) return usageError("--out is required");
    return -1;
}

// The files the options name, before any work: the outputs can be written and are neither the mesh
// nor each other, the cache is a usable directory.
spatter::Status checkFiles(const Options& o) {
    using spatter::cli::NamedPath;
    const NamedPath out{"--out", o.out}, report{"--report", o.report};
    if (spatter::Status s = spatter::cli::distinctFiles({out, report}, {{"MESH", o.mesh}}); !s) return s;
    for (const NamedPath& output : {out, report})
        if (!output.path.empty())
            if (spatter::Status s = spatter::cli::creatableFile(output); !s) return s;
    if (!o.settings.cacheDirectory.empty())
        return spatter::cli::usableDirectory({"--cache", o.settings.cacheDirectory});
    return {};
}

// The report: sizes, the backend, the tolerance and the distances in world units, the time.
nlohmann::ordered_json reportOf(const spatter::Proxy& proxy) {
    nlohmann::ordered_json r;
    r["input_triangles"] = proxy.inputTriangles;
    r["proxy_triangles"] = proxy.proxyTriangles;
    r["backend"] = spatter::proxyBackendName(proxy.backend);
    r["tolerance"] = proxy.tolerance;
    r["error_bound"] = proxy.errorBound;
    r["proxy_to_render_max"] = proxy.proxyToRenderMax;
    r["render_to_proxy_max"] = proxy.renderToProxyMax;
    r["seconds"] = proxy.seconds;
    r["cached"] = proxy.cached;
    return r;
}

} // namespace

int main(int argc, char** argv) {
    if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (argc < 3 || std::strcmp(argv[1], "build") != 0) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    Options options;
    if (const int exitCode = parseOptions(argc, argv, options); exitCode >= 0) return exitCode;
    if (spatter::Status s = checkFiles(options); !s) return usageError(s.error());
    const std::string &mesh = options.mesh, &out = options.out, &report = options.report;
    const bool quiet = options.quiet;
    const spatter::ProxySettings& settings = options.settings;

    spatter::Result<spatter::Scene> scene = spatter::loadScene(mesh);
    if (!scene) {
        std::cerr << "spatter-proxy: " << scene.error() << "\n";
        return 1;
    }
    for (const std::string& w : scene->warnings)
        std::cerr << "spatter-proxy: warning: " << w << "\n";
    const spatter::Mesh world = mergeWorld(scene.value());
    for (const spatter::SceneObject& object : scene->objects)
        if (object.collider && !quiet)
            std::cerr << "spatter-proxy: note: object '" << object.name
                      << "' has an authored collider; this tool simplifies the merged render meshes\n";

    ProgressPrinter printer;
    spatter::ProgressCallback progress;
    if (!quiet) progress = [&printer](float f, const char* stage) { return printer(f, stage); };
    spatter::Result<spatter::Proxy> proxy = spatter::buildProxy(world, settings, nullptr, progress);
    printer.finish();
    if (!proxy) {
        std::cerr << "spatter-proxy: " << mesh << ": " << proxy.error() << "\n";
        return 1;
    }
    if (!quiet)
        for (const std::string& note : proxy->notes)
            std::cerr << "spatter-proxy: note: " << note << "\n";
    spatter::cli::OutputCleanup cleanup; // the outputs of a run that fails
    cleanup.writing(out);
    if (spatter::Status written = spatter::writeObj(proxy->mesh, out, objComment(proxy.value())); !written) {
        std::cerr << "spatter-proxy: " << written.error() << "\n";
        return 1;
    }
    if (!report.empty()) {
        cleanup.writing(report);
        std::ofstream f(report);
        f << reportOf(proxy.value()).dump(2) << "\n";
        f.close();
        if (!f) {
            std::cerr << "spatter-proxy: cannot write " << report << "\n";
            return 1;
        }
    }
    cleanup.keep();
    if (!quiet)
        std::cerr << "spatter-proxy: " << proxy->inputTriangles << " -> " << proxy->proxyTriangles
                  << " triangles (" << spatter::proxySourceName(proxy->source) << ", "
                  << spatter::proxyBackendName(proxy->backend) << "), h = " << proxy->errorBound
                  << " (tolerance " << proxy->tolerance << "), " << proxy->seconds << " s"
                  << (proxy->cached ? ", cached" : "") << "\n";
    return 0;
}
