#pragma once
// The numerical stress cases shared by the `stress` test suite (tests/stress) and
// `spatter-bench stress`: both run exactly this code, the tests at CI size, the bench at full size.
//
// A case measures one or more errors (rows). Each row holds the largest error measured over every
// input the case tried and the bound it must stay within; the case passes when every row does.
// Rows marked informational are shown for comparison (e.g. a standard-Z depth buffer) and never fail.

#include "spatter/render/GlContext.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace spatter::stress {

struct StressConfig {
    bool full = false;       // full size (the bench) instead of CI size (the tests)
    uint64_t seed = 1;       // every random input derives from it
    std::string dataDir;     // ../shared/data (fandisk); empty: the parts that need it are skipped
    std::string placeTool;   // the spatter-place binary; empty: the tool part is skipped
    std::string scratchDir;  // an existing empty directory for files the cases write
    GlContext* gl = nullptr; // current headless context; nullptr: GPU parts are skipped
    std::string glError;     // why there is no context
};

struct StressRow {
    std::string metric;         // what is measured, with its unit
    double worst = 0.0;         // largest error measured (NaN counts as a failure)
    double bound = 0.0;         // the row passes when worst <= bound over at least one input
    size_t samples = 0;         // inputs measured
    std::string note;           // where the worst value was, or how it was measured
    bool informational = false; // shown for comparison; never fails

    bool pass() const { return informational || (samples > 0 && worst <= bound); }
};

struct StressResult {
    std::string name;
    std::string technique; // what holds the bound, with its reference
    std::vector<StressRow> rows;
    std::vector<std::string> failures; // the first failing inputs, described
    std::string skipped;               // non-empty: the case could not run, and why
    double seconds = 0.0;

    // Every row passes.
    bool pass() const;
    // Adds a row; returns it for further fields.
    StressRow& row(const std::string& metric, double worst, double bound, size_t samples,
                   const std::string& note = "");
    // Records a failing input (kept up to a limit).
    void failure(const std::string& what);
};

// Largest of a and b where NaN wins, so that a NaN error can never hide behind a max.
double worse(double a, double b);

struct StressCase {
    const char* name;    // e.g. "frames"
    const char* summary; // one line
    StressResult (*run)(const StressConfig& config);
};

// Every case, in report order.
const std::vector<StressCase>& stressCases();

// The cases, one function each (defined in <Name>Stress.cpp).
StressResult runFrames(const StressConfig& config);
StressResult runGrazing(const StressConfig& config);
StressResult runWatertight(const StressConfig& config);
StressResult runDegenerate(const StressConfig& config);
StressResult runFarPlacement(const StressConfig& config);
StressResult runFarTool(const StressConfig& config);
StressResult runFarRender(const StressConfig& config);
StressResult runExtremeSizes(const StressConfig& config);
StressResult runExtremeSizesRender(const StressConfig& config);
StressResult runDepth(const StressConfig& config);
StressResult runNonFinitePlacement(const StressConfig& config);
StressResult runNonFiniteRender(const StressConfig& config);
StressResult runSoak(const StressConfig& config);

// Runs one case, timing it and catching nothing (the library throws nothing).
StressResult runCase(const StressCase& c, const StressConfig& config);

} // namespace spatter::stress
