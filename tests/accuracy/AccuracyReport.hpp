#pragma once
// The figures of the mismatch tests as Markdown tables (the tables of docs/ACCURACY.md).
//
// Every measured case is recorded with recordCase; when the environment variable
// SPATTER_ACCURACY_REPORT names a file, the tables of all cases recorded in the process are written
// to it after the last test (run the test executable itself, not through ctest, which starts one
// process per test). Without the variable nothing is written.

#include "Mismatch.hpp"

#include <string>
#include <vector>

namespace spatter::test {

// What the proxy builder returned for one object (by its index in Scene::objects).
struct ProxyFacts {
    std::string kind;         // "meshopt", "openmesh" or "own mesh"
    bool toleranceMet = true; // h <= the tolerance asked for
};

struct CaseReport {
    std::string mesh;       // label of the mesh or scene
    double tolerance = 0.0; // relative to each object's bounding diagonal
    std::vector<ObjectMismatch> objects;
    std::vector<ProxyFacts> proxies; // one per Scene object
    double buildSeconds = 0.0;       // building every proxy of the case
    double measureSeconds = 0.0;     // worlds, rays, queries and decals
    bool perObject = false;          // also write one row per object
};

void recordCase(CaseReport report);

// The Markdown tables of `cases`: one row per case (objects pooled), then, for cases with
// perObject, one table per case with a row per object.
std::string accuracyTables(const std::vector<CaseReport>& cases);

} // namespace spatter::test
