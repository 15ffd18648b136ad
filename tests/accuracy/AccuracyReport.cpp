#include "AccuracyReport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>

namespace spatter::test {

namespace {

std::mutex gMutex;
std::vector<CaseReport> gCases;

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

std::string count(size_t n) {
    std::string s = std::to_string(n), out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (i > 0 && (s.size() - i) % 3 == 0) out += ',';
        out += s[i];
    }
    return out;
}

std::string percent(double fraction) {
    return fmt("%.3g", 100.0 * fraction);
}

std::string triple(const Distribution& d, double scale, const char* format) {
    if (d.count == 0) return "-";
    return fmt(format, d.p50 * scale) + " / " + fmt(format, d.p99 * scale) + " / " +
           fmt(format, d.max * scale);
}

// The figures of a set of objects pooled into one row.
struct Pooled {
    std::string proxy;
    size_t renderTriangles = 0, proxyTriangles = 0, rays = 0, proxyHits = 0;
    size_t disagreements = 0, proxyOnly = 0, renderOnly = 0, otherObject = 0;
    size_t decals = 0, holding = 0, tightDecals = 0, tightHolding = 0, beyond = 0, shotDecals = 0,
           shotInSlab = 0;
    double hRelative = 0.0;   // largest h / diagonal
    double distanceRatio = 0; // largest proxy-hit distance / h over objects with h > 0
    double exactDistance = 0; // largest proxy-hit distance / diagonal over objects with h = 0
    bool anyExact = false, anyBounded = false, allMet = true;
    double defaultDepthUse = 0.0, tightDepthUse = 0.0, lateralUse = 0.0, shotLateralUse = 0.0;
    std::vector<double> offsets, angles;
};

Pooled pool(const CaseReport& c, const std::vector<const ObjectMismatch*>& objects) {
    Pooled p;
    std::map<std::string, size_t> kinds;
    for (const ObjectMismatch* o : objects) {
        const ProxyFacts facts = o->object < c.proxies.size() ? c.proxies[o->object] : ProxyFacts{};
        kinds[facts.kind]++;
        p.allMet = p.allMet && facts.toleranceMet;
        p.renderTriangles += o->renderTriangles;
        p.proxyTriangles += o->proxyTriangles;
        p.rays += o->rays;
        p.proxyHits += o->proxyHits;
        p.proxyOnly += o->proxyOnly;
        p.renderOnly += o->renderOnly;
        p.otherObject += o->otherObject;
        p.disagreements += o->disagreements();
        p.decals += o->decals;
        p.holding += o->decalsHolding;
        p.tightDecals += o->tightDecals;
        p.tightHolding += o->tightHolding;
        p.beyond += o->hitsBeyondBound;
        p.shotDecals += o->shotDecals;
        p.shotInSlab += o->shotInSlab;
        p.shotLateralUse = std::max(p.shotLateralUse, o->shotLateralUse);
        p.defaultDepthUse = std::max(p.defaultDepthUse, o->defaultDepthUse);
        p.tightDepthUse = std::max(p.tightDepthUse, o->tightDepthUse);
        p.lateralUse = std::max(p.lateralUse, o->lateralUse);
        if (o->diagonal > 0.0) p.hRelative = std::max(p.hRelative, o->errorBound / o->diagonal);
        if (o->errorBound > 0.0) {
            p.anyBounded = true;
            p.distanceRatio = std::max(p.distanceRatio, o->maxHitDistance / o->errorBound);
        } else if (o->proxyHits > 0) {
            p.anyExact = true;
            p.exactDistance =
                std::max(p.exactDistance, o->diagonal > 0.0 ? o->maxHitDistance / o->diagonal : 0.0);
        }
        p.offsets.insert(p.offsets.end(), o->offsets.begin(), o->offsets.end());
        p.angles.insert(p.angles.end(), o->angles.begin(), o->angles.end());
    }
    for (const auto& [kind, n] : kinds)
        p.proxy += (p.proxy.empty() ? "" : ", ") + kind + (kinds.size() > 1 ? " x" + std::to_string(n) : "");
    return p;
}

const char* kHeader =
    "| %s | tol | proxy | triangles render -> proxy | h (%% of diag) | max d / h | along-ray offset "
    "p50 / p99 / max (%% of diag) | normal angle p50 / p99 / max (deg) | hit/miss disagreement | decal "
    "boxes holding the nearest render point (default / tight) | nearest render point: largest \\|z\\| / "
    "half-depth (default, tight); lateral | along the shot: render hits within the half-depth; largest "
    "\\|u\\|, \\|v\\| | rays (proxy hits) |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

std::string row(const std::string& label, const CaseReport& c, const Pooled& p) {
    std::string distance;
    if (p.anyBounded) distance = fmt("%.3f", p.distanceRatio);
    if (p.anyExact)
        distance += std::string(distance.empty() ? "" : "; ") +
                    "h = 0: d <= " + fmt("%.1e", p.exactDistance) + " diag";
    if (p.beyond > 0) distance += " **" + count(p.beyond) + " beyond h**";
    const double rate = p.rays > 0 ? double(p.disagreements) / double(p.rays) : 0.0;
    std::string disagreement = percent(rate) + "%";
    if (p.disagreements > 0)
        disagreement += " (" + count(p.proxyOnly) + " proxy only, " + count(p.renderOnly) + " render only" +
                        (p.otherObject > 0 ? ", " + count(p.otherObject) + " other object" : "") + ")";
    return "| " + label + " | " + percent(c.tolerance) + "% | " + p.proxy + " | " + count(p.renderTriangles) +
           " -> " + count(p.proxyTriangles) + " | " + fmt("%.3g", 100.0 * p.hRelative) +
           (p.allMet ? "" : " (above tol)") + " | " + distance + " | " +
           triple(summarize(p.offsets), 100.0, "%.2g") + " | " + triple(summarize(p.angles), 1.0, "%.2g") +
           " | " + disagreement + " | " + count(p.holding) + " of " + count(p.decals) + " / " +
           count(p.tightHolding) + " of " + count(p.tightDecals) + " | " + fmt("%.3f", p.defaultDepthUse) +
           ", " + fmt("%.3f", p.tightDepthUse) + "; " + fmt("%.3f", p.lateralUse) + " | " +
           count(p.shotInSlab) + " of " + count(p.shotDecals) + "; " + fmt("%.4f", p.shotLateralUse) + " | " +
           count(p.rays) + " (" + count(p.proxyHits) + ") |\n";
}

class ReportEnvironment : public ::testing::Environment {
public:
    void TearDown() override {
        const char* path = std::getenv("SPATTER_ACCURACY_REPORT");
        if (!path || !*path) return;
        std::lock_guard<std::mutex> lock(gMutex);
        std::ofstream out(path);
        out << accuracyTables(gCases);
        if (!out)
            std::fprintf(stderr, "cannot write the accuracy report to %s\n", path);
        else
            std::printf("accuracy report written to %s (%zu cases)\n", path, gCases.size());
    }
};

const ::testing::Environment* const gEnvironment = ::testing::AddGlobalTestEnvironment(new ReportEnvironment);

} // namespace

void recordCase(CaseReport report) {
    std::lock_guard<std::mutex> lock(gMutex);
    gCases.push_back(std::move(report));
}

std::string accuracyTables(const std::vector<CaseReport>& cases) {
    std::string md;
    char header[1024];
    std::snprintf(header, sizeof header, kHeader, "mesh");
    md += header;
    for (const CaseReport& c : cases) {
        std::vector<const ObjectMismatch*> all;
        for (const ObjectMismatch& o : c.objects)
            all.push_back(&o);
        const std::string label =
            c.objects.size() == 1 ? c.mesh : c.mesh + " (" + std::to_string(c.objects.size()) + " objects)";
        md += row(label, c, pool(c, all));
    }
    for (const CaseReport& c : cases) {
        if (!c.perObject) continue;
        md += "\n**" + c.mesh + " at " + percent(c.tolerance) + "%**, per object (proxies built in " +
              fmt("%.1f", c.buildSeconds) + " s):\n\n";
        std::snprintf(header, sizeof header, kHeader, "object");
        md += header;
        for (const ObjectMismatch& o : c.objects)
            md += row(o.name, c, pool(c, {&o}));
    }
    md += "\nBuild and measurement time per case (s):\n\n| mesh | tol | proxies | measurement "
          "|\n|---|---|---|---|\n";
    for (const CaseReport& c : cases)
        md += "| " + c.mesh + " | " + percent(c.tolerance) + "% | " + fmt("%.2f", c.buildSeconds) + " | " +
              fmt("%.2f", c.measureSeconds) + " |\n";
    return md;
}

} // namespace spatter::test
