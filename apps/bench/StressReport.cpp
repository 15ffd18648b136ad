#include "StressReport.hpp"

#include "BenchSupport.hpp"
#include "StressCase.hpp"

#include "spatter/render/GlContext.hpp"

#include "cli/Arguments.hpp"
#include "cli/Numbers.hpp"
#include "cli/PathChecks.hpp"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

namespace fs = std::filesystem;
using stress::StressCase;
using stress::StressConfig;
using stress::StressResult;
using stress::StressRow;

const char* kStressUsage =
    R"(usage: spatter-bench stress [--json FILE] [--quick] [--case NAME]... [--data DIR]
                            [--place-tool PATH] [--seed N] [--no-gpu]

Runs the numerical stress cases at full size (the `stress` tests run the same code at CI size) and
prints one line per measurement: the case, what is measured, the largest error measured, its bound,
the number of samples, and pass, FAIL or info (shown for comparison, no bound).

Options:
  --json FILE        also write every number (and the first failing inputs) as JSON
  --quick            the CI sizes instead of the full ones
  --case NAME        run only this case (repeatable); names are listed below
  --data DIR         the shared data directory (fandisk); default $SPATTER_SHARED_DATA or ../shared/data
  --place-tool PATH  the spatter-place binary, an executable file; default: next to
                     spatter-bench, else the build's
  --seed N           seed of every random input, a whole number (default 1)
  --no-gpu           do not create an OpenGL context (the GPU cases are skipped)

Exit code 0 when every case that ran passes (a case that could not run, such as a GPU case without
an OpenGL context, is listed as skipped), 1 when one fails, 2 on bad options (an option other than
--case given twice, a --json FILE that cannot be written, checked before the cases run).

Cases:
)";

bool exists(const std::string& path) {
    std::error_code ec;
    return !path.empty() && fs::exists(path, ec);
}

std::string selfDirectory() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : self.parent_path().string();
}

std::string defaultPlaceTool() {
    const std::string sibling = selfDirectory() + "/spatter-place";
    if (exists(sibling)) return sibling;
    return exists(SPATTER_BENCH_PLACE_TOOL) ? SPATTER_BENCH_PLACE_TOOL : "";
}

std::string defaultDataDir() {
    if (const char* env = std::getenv("SPATTER_SHARED_DATA"); env && *env) return env;
    return exists(SPATTER_BENCH_SHARED_DATA) ? fs::path(SPATTER_BENCH_SHARED_DATA).lexically_normal().string()
                                             : "";
}

const char* verdict(const StressRow& row) {
    if (row.informational) return "info";
    return row.pass() ? "pass" : "FAIL";
}

nlohmann::ordered_json orderedNumber(double v) {
    if (std::isfinite(v)) return v;
    return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

void printCase(const StressResult& r) {
    if (!r.skipped.empty()) {
        std::printf("%-22s skipped: %s\n", r.name.c_str(), r.skipped.c_str());
        return;
    }
    for (const StressRow& row : r.rows)
        std::printf("%-22s %-92s %-11.3g %-9.3g %-9zu %s\n", r.name.c_str(), row.metric.c_str(), row.worst,
                    row.bound, row.samples, verdict(row));
    for (const std::string& f : r.failures)
        if (!r.pass()) std::printf("%-22s   failing input: %s\n", r.name.c_str(), f.c_str());
    std::fflush(stdout);
}

nlohmann::ordered_json toJson(const StressResult& r) {
    nlohmann::ordered_json j;
    j["name"] = r.name;
    j["technique"] = r.technique;
    j["seconds"] = r.seconds;
    j["skipped"] = r.skipped;
    j["pass"] = r.pass();
    j["rows"] = nlohmann::ordered_json::array();
    for (const StressRow& row : r.rows) {
        nlohmann::ordered_json x;
        x["metric"] = row.metric;
        x["worst"] = orderedNumber(row.worst);
        x["bound"] = orderedNumber(row.bound);
        x["samples"] = row.samples;
        x["note"] = row.note;
        x["informational"] = row.informational;
        x["verdict"] = verdict(row);
        j["rows"].push_back(std::move(x));
    }
    j["failures"] = r.failures;
    return j;
}

int usageError(const std::string& message) {
    std::cerr << "spatter-bench stress: " << message << "\n(see spatter-bench stress --help)\n";
    return 2;
}

} // namespace

int runStressCommand(int argc, char** argv) {
    StressConfig config;
    config.full = true;
    config.dataDir = defaultDataDir();
    config.placeTool = defaultPlaceTool();
    std::string jsonPath;
    std::vector<std::string> only;
    bool gpu = true;
    bool placeToolGiven = false;
    cli::Arguments args(argc, argv, 1, {"--case"});
    while (args.more()) {
        const Result<std::string> next = args.next();
        if (!next) return usageError(next.error());
        const std::string& a = next.value();
        auto value = [&](std::string& out) {
            const std::optional<std::string> v = args.value();
            if (v) out = *v;
            return v.has_value();
        };
        if (a == "--help" || a == "-h") {
            std::cout << kStressUsage;
            for (const StressCase& c : stress::stressCases())
                std::printf("  %-22s %s\n", c.name, c.summary);
            return 0;
        } else if (a == "--json") {
            if (!value(jsonPath) || jsonPath.empty()) return usageError("--json needs a file");
        } else if (a == "--quick") {
            config.full = false;
        } else if (a == "--case") {
            std::string name;
            if (!value(name)) return usageError("--case needs a name");
            bool known = false;
            for (const StressCase& c : stress::stressCases())
                known = known || name == c.name;
            if (!known) return usageError("no case named '" + name + "'");
            only.push_back(name);
        } else if (a == "--data") {
            if (!value(config.dataDir)) return usageError("--data needs a directory");
        } else if (a == "--place-tool") {
            if (!value(config.placeTool)) return usageError("--place-tool needs a path");
            placeToolGiven = true;
        } else if (a == "--seed") {
            std::string v;
            if (!value(v) || !cli::parseWhole(v, UINT64_MAX, config.seed))
                return usageError("--seed needs a whole number in 0.." + std::to_string(UINT64_MAX));
        } else if (a == "--no-gpu") {
            gpu = false;
        } else {
            return usageError("unknown option " + a);
        }
    }
    if (placeToolGiven)
        if (Status s = cli::executableFile({"--place-tool", config.placeTool}); !s)
            return usageError(s.error());
    if (!jsonPath.empty())
        if (Status s = cli::creatableFile({"--json", jsonPath}); !s) return usageError(s.error());

    std::optional<GlContext> context;
    if (gpu) {
        Result<GlContext> gl = GlContext::createHeadless();
        if (gl) {
            context.emplace(std::move(gl).value());
            config.gl = &*context;
        } else {
            config.glError = gl.error();
        }
    } else {
        config.glError = "--no-gpu";
    }
    const ScratchDirectory scratch("stress");
    if (!scratch.error().empty()) return usageError(scratch.error());
    config.scratchDir = scratch.path();

    std::printf("spatter-bench stress: %s size, seed %llu\n", config.full ? "full" : "CI",
                static_cast<unsigned long long>(config.seed));
    std::printf("  GL: %s\n",
                config.gl ? (config.gl->info().renderer + " (" + config.gl->info().platform + ")").c_str()
                          : ("none: " + config.glError).c_str());
    std::printf("  shared data: %s\n", config.dataDir.empty() ? "none" : config.dataDir.c_str());
    std::printf("  spatter-place: %s\n\n", config.placeTool.empty() ? "none" : config.placeTool.c_str());
    std::printf("%-22s %-92s %-11s %-9s %-9s %s\n", "case", "measured", "worst", "bound", "samples",
                "result");

    nlohmann::ordered_json report;
    report["size"] = config.full ? "full" : "ci";
    report["seed"] = config.seed;
    report["gl_renderer"] = config.gl ? config.gl->info().renderer : "";
    report["gl_version"] = config.gl ? config.gl->info().version : "";
    report["cases"] = nlohmann::ordered_json::array();
    bool allPass = true;
    std::vector<std::string> skipped;
    for (const StressCase& c : stress::stressCases()) {
        bool wanted = only.empty();
        for (const std::string& name : only)
            wanted = wanted || name == c.name;
        if (!wanted) continue;
        const StressResult r = stress::runCase(c, config);
        printCase(r);
        allPass = allPass && r.pass();
        if (!r.skipped.empty()) skipped.push_back(r.name);
        report["cases"].push_back(toJson(r));
    }
    report["pass"] = allPass;
    report["skipped"] = skipped;
    if (!jsonPath.empty())
        if (Status s = writeJson(report, jsonPath); !s) {
            std::cerr << "spatter-bench stress: " << s.error() << "\n";
            return 1;
        }
    if (!allPass)
        std::printf("\nSOME CASES FAIL\n");
    else if (skipped.empty())
        std::printf("\nevery case passes\n");
    else
        std::printf("\nevery case that ran passes; %zu could not run (above)\n", skipped.size());
    return allPass ? 0 : 1;
}

} // namespace spatter::bench
