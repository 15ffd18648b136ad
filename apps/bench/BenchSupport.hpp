#pragma once
// What the benchmark commands of spatter-bench share: command-line parsing, clocks and statistics,
// the machine description, input meshes (merged scenes, Loop subdivision, OBJ export), seeded ray
// sets, memory readings, tables and JSON output.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/Ray.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace spatter::bench {

using Json = nlohmann::ordered_json;

constexpr double kPi = 3.14159265358979323846;

// ---- Command line ----------------------------------------------------------------------------

// argv split into positional arguments, "--name value" options and "--flag" switches.
struct Args {
    std::vector<std::string> positional;
    std::map<std::string, std::string> values;
    std::set<std::string> flags;

    bool has(const std::string& name) const { return values.count(name) > 0 || flags.count(name) > 0; }
    std::string value(const std::string& name, const std::string& fallback = "") const;
};

// Parses argv[1..argc) (argv[0] is the command's name). `valued` lists the options that take a
// value, `switches` those that do not; anything else starting with "--" is an error naming it, as
// are an option given twice and a value that is missing or starts with "--". A --json FILE must be
// a file that can be written (checked here, before the command's work).
Result<Args> parseArgs(int argc, char** argv, const std::set<std::string>& valued,
                       const std::set<std::string>& switches);

// A finite decimal number (cli::parseDecimal: no blanks, no hexadecimal), or an error naming the
// option.
Result<double> parseNumber(const std::string& text, const std::string& option);
// A whole number below 2^63, digits only, or an error naming the option.
Result<uint64_t> parseCount(const std::string& text, const std::string& option);
// Fails, naming the option, unless `text` is a filter google benchmark compiles: a POSIX extended
// regular expression, after a leading '-' (which negates it).
Status checkFilter(const std::string& text, const std::string& option);
// Comma-separated finite numbers.
Result<std::vector<double>> parseNumberList(const std::string& text, const std::string& option);

// Prints "spatter-bench COMMAND: message" and the hint to --help on stderr; returns 2.
int usageError(const std::string& command, const std::string& message);

// How every command starts: argv parsed by parseArgs, with --help and -h added to `switches`.
// Returns the arguments; or nothing, with `exitCode` set to what the command returns at once: 0
// after printing `usage` on stdout for --help or -h, 2 after a usage error (usageError).
std::optional<Args> commandArgs(int argc, char** argv, const std::string& command, const std::string& usage,
                                const std::set<std::string>& valued, std::set<std::string> switches,
                                int& exitCode);

// ---- Clocks and statistics -------------------------------------------------------------------

inline double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU time of the calling thread, seconds: single-threaded loops timed with it are not slowed down by
// other processes on a shared machine (the tables say which clock they use).
double threadCpuNow();

// Nearest-rank percentile (q in [0, 1]) of `values`; 0 for an empty sample.
double percentile(std::vector<double> values, double q);
double median(std::vector<double> values);
// The median of get(item) over `items`.
template <class T, class Get> double medianOf(const std::vector<T>& items, Get&& get) {
    std::vector<double> values;
    values.reserve(items.size());
    for (const T& item : items)
        values.push_back(get(item));
    return median(std::move(values));
}

// ---- The machine -----------------------------------------------------------------------------

struct MachineInfo {
    std::string cpu;     // "model name" of /proc/cpuinfo
    unsigned threads;    // hardware threads
    std::string loadavg; // the three load averages of /proc/loadavg when the command started
};
MachineInfo machineInfo();
Json toJson(const MachineInfo& m);
// One line: "CPU (N threads), load a b c".
std::string describe(const MachineInfo& m);

// ---- Input meshes ----------------------------------------------------------------------------

// The shared data directory: $SPATTER_SHARED_DATA, else ../shared/data of the source tree when it
// exists, else empty.
std::string sharedDataDir();

// `spec` as loadScene takes it: builtin names and existing paths as they are; otherwise the path
// inside the shared data (as given, then under meshes/). Empty when nothing is found.
std::string resolveInput(const std::string& spec);

// Every decal receiver of `scene` merged into one mesh in world space (transforms applied in
// double), with area-weighted normals. Authored colliders are not used.
Mesh mergeReceivers(const Scene& scene);

// The input mesh of a benchmark: `spec` loaded (resolveInput, loadScene), its receivers merged,
// then subdivided `loopSteps` times (loopSubdivide). `name` is a short label: the file stem, plus "-loopN".
struct InputMesh {
    std::string name;
    std::string source; // `spec` as given
    Mesh mesh;
    double diagonal = 0.0; // of the referenced vertices
    size_t droppedFaces = 0;
};
Result<InputMesh> loadInputMesh(const std::string& spec, int loopSteps);

// Diagonal of the bounding box of the vertices the triangles use; 0 without triangles.
double referencedDiagonal(const Mesh& mesh);

// A scene with `mesh` as its one static object.
Scene singleObjectScene(const Mesh& mesh, const std::string& name);

// ---- Rays ------------------------------------------------------------------------------------

// Area-weighted random points on a mesh's surface.
class SurfaceSampler {
public:
    explicit SurfaceSampler(const Mesh& mesh);
    bool empty() const { return cumulative_.empty() || cumulative_.back() <= 0.0; }
    // Uniform u, v, w in [0, 1): a point of the triangle chosen by area.
    glm::dvec3 sample(float u, float v, float w) const;

private:
    const Mesh& mesh_;
    std::vector<double> cumulative_;
};

// `count` rays from random points of the sphere of 1.5 times the bounding radius around the mesh,
// 90% aimed at area-weighted random points of its surface and 10% at random points of its bounds.
std::vector<Ray> scatteredRays(const Mesh& mesh, size_t count, uint64_t seed);

// `batches` shotgun shots: each from a random point of that sphere, aimed at a random surface
// point, `raysPerBatch` rays uniform in the cone of apex angle `coneDeg` around the aim. Rays of a
// batch are consecutive.
std::vector<Ray> shotgunRays(const Mesh& mesh, size_t batches, size_t raysPerBatch, double coneDeg,
                             uint64_t seed);

// A direction uniform over the cone of half-angle `halfAngle` (radians) around unit `axis`.
glm::dvec3 randomConeDirection(const glm::dvec3& axis, double halfAngle, Rng& rng);

// Writes rays as the ray files of spatter-place read them: "ox oy oz dx dy dz" per line.
Status writeRays(const std::vector<Ray>& rays, const std::string& path);

// ---- Output ----------------------------------------------------------------------------------

// Prints `rows` under `header`, columns padded to their widest cell; numbers right-aligned.
void printTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

// "%.3g"-style formatting with a fixed number of significant digits; "-" for NaN.
std::string fmt(double v, int digits = 3);
// Milliseconds, nanoseconds etc. with `decimals` after the point; "-" for NaN.
std::string fixed(double v, int decimals);

// A JSON number, or null when not finite.
Json number(double v);

// Writes `j` (indented) to `path`. Fails naming the file.
Status writeJson(const Json& j, const std::string& path);

// A fresh directory under the system temp directory (unique per process and name), removed with
// everything in it when this object goes.
class ScratchDirectory {
public:
    explicit ScratchDirectory(const std::string& name);
    ~ScratchDirectory();
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;

    const std::string& path() const { return path_; }
    // Empty when the directory could not be made.
    const std::string& error() const { return error_; }

private:
    std::string path_, error_;
};

} // namespace spatter::bench
