#include "spatter/placement/TraceTransform.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace spatter {

namespace {

// The linear part rounded to float, as Embree receives it, widened back to double (exactly).
glm::dmat3 floatLinear(const glm::dmat4& m) {
    glm::dmat3 a;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            a[c][r] = double(float(m[c][r]));
    return a;
}

double frobenius(const glm::dmat3& a) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c)
        s += glm::dot(a[c], a[c]);
    return std::sqrt(s);
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

std::string limit(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", v);
    return text;
}

// |A|_F and |A^-1|_F of the float matrix; the inverse's norm is infinite when it does not exist.
void norms(const glm::dmat4& transform, double& forward, double& inverse) {
    const glm::dmat3 a = floatLinear(transform);
    forward = frobenius(a);
    const double det = glm::determinant(a);
    inverse = std::numeric_limits<double>::infinity();
    if (det == 0.0 || !std::isfinite(det) || !std::isfinite(forward)) return;
    const double n = frobenius(glm::inverse(a));
    if (std::isfinite(n)) inverse = n;
}

} // namespace

double floatConditionNumber(const glm::dmat4& transform) {
    double forward, inverse;
    norms(transform, forward, inverse);
    const double k = forward * inverse;
    return std::isfinite(k) ? k : std::numeric_limits<double>::infinity(); // also 0 * inf
}

std::string floatLinearProblem(const glm::dmat4& transform) {
    double forward, inverse;
    norms(transform, forward, inverse);
    const double product = forward * inverse;
    const double condition = std::isfinite(product) ? product : std::numeric_limits<double>::infinity();
    if (condition > kTraceMaxCondition)
        return "transform is " + std::string(std::isfinite(condition) ? "nearly " : "") +
               "singular in single precision (condition number " + number(condition) + ", limit " +
               limit(kTraceMaxCondition) + ")";
    if (forward > kTraceMaxScale)
        return "transform scales by more than single precision allows (norm " + number(forward) + ", limit " +
               limit(kTraceMaxScale) + ")";
    if (inverse > kTraceMaxScale)
        return "transform scales by less than single precision allows (inverse norm " + number(inverse) +
               ", limit " + limit(kTraceMaxScale) + ")";
    return {};
}

std::string tracePlacementProblem(const glm::dmat4& transform, const Bounds& local,
                                  const glm::dvec3& frameOrigin) {
    if (local.empty()) return {};
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p((i & 1) ? local.max.x : local.min.x, (i & 2) ? local.max.y : local.min.y,
                           (i & 4) ? local.max.z : local.min.z);
        const glm::dvec3 f = glm::dvec3(transform * glm::dvec4(p, 1.0)) - frameOrigin;
        lo = glm::min(lo, f);
        hi = glm::max(hi, f);
    }
    const glm::dvec3 far = glm::max(glm::abs(lo), glm::abs(hi)), size = hi - lo;
    const double reach = std::fmax(far.x, std::fmax(far.y, far.z));
    const double extent = std::fmax(size.x, std::fmax(size.y, size.z));
    if (!(reach <= kTraceMaxFrameExtent))
        return "object lies " + number(reach) + " from the collision world's origin, beyond the " +
               limit(kTraceMaxFrameExtent) + " single precision keeps";
    if (!(extent > 0.0)) return "collision mesh is a single point";
    if (extent < kTraceMinRelativeSize * reach)
        return "object is too small for single precision at its place (size " + number(extent) + " at " +
               number(reach) + " from the collision world's origin)";
    return {};
}

std::string traceTransformProblem(const glm::dmat4& transform, const Bounds& local,
                                  const glm::dvec3& frameOrigin) {
    std::string problem = floatLinearProblem(transform);
    return problem.empty() ? tracePlacementProblem(transform, local, frameOrigin) : problem;
}

} // namespace spatter
