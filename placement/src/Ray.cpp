#include "spatter/placement/Ray.hpp"
#include "NumberChecks.hpp"

#include <cfloat>
#include <cmath>

namespace spatter {

const char* rayProblem(const Ray& ray) {
    if (!finite3(ray.origin)) return "ray origin is not finite";
    if (!finite3(ray.direction)) return "ray direction is not finite";
    const glm::dvec3& d = ray.direction;
    if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) return "ray direction is zero";
    const double len2 = d.x * d.x + d.y * d.y + d.z * d.z;
    if (!(len2 >= DBL_MIN)) return "ray direction is denormal (its squared length underflows)";
    if (!std::isfinite(len2)) return "ray direction is too long (its squared length overflows)";
    if (std::isnan(ray.tnear)) return "ray tnear is NaN";
    if (!std::isfinite(ray.tnear)) return "ray tnear is infinite";
    if (ray.tnear < 0.0) return "ray tnear is negative";
    if (std::isnan(ray.tfar)) return "ray tfar is NaN";
    if (!(ray.tfar > ray.tnear)) return "ray tfar is not greater than tnear";
    return nullptr;
}

} // namespace spatter
