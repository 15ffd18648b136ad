#include "spatter/render/Camera.hpp"

#include "spatter/core/TextFields.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace spatter {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string exactNumber(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

} // namespace

Result<Camera> parseCamera(const std::string& text) {
    Camera cam;
    bool haveEye = false, haveTarget = false, haveUp = false, haveFov = false;
    for (const std::string& rawItem : splitFields(text, ';')) {
        const std::string item = trimBlanks(rawItem);
        if (item.empty()) continue;
        const size_t eq = item.find('=');
        if (eq == std::string::npos) return fail("camera: item '" + item + "' is not key=value");
        const std::string key = trimBlanks(item.substr(0, eq));
        const std::string value = item.substr(eq + 1);
        if (key == "fov") {
            if (haveFov) return fail("camera: fov given twice");
            haveFov = true;
            const std::string field = trimBlanks(value);
            if (!parseDecimal(field, cam.fovYDeg)) return fail("camera: fov '" + field + "' is not a number");
            continue;
        }
        struct Slot {
            const char* key;
            glm::dvec3* value;
            bool* seen;
        };
        const Slot slots[] = {
            {"eye", &cam.eye, &haveEye}, {"target", &cam.target, &haveTarget}, {"up", &cam.up, &haveUp}};
        const Slot* slot = nullptr;
        for (const Slot& sl : slots)
            if (key == sl.key) slot = &sl;
        if (!slot) return fail("camera: unknown key '" + key + "' (expected eye, target, up, fov)");
        if (*slot->seen) return fail("camera: " + key + " given twice");
        *slot->seen = true;
        glm::dvec3* dst = slot->value;
        const std::vector<std::string> parts = splitFields(value, ',');
        if (parts.size() != 3) return fail("camera: " + key + " needs three comma-separated numbers");
        for (int k = 0; k < 3; ++k) {
            const std::string field = trimBlanks(parts[size_t(k)]);
            if (!parseDecimal(field, (*dst)[k]))
                return fail("camera: " + key + " component '" + field + "' is not a number");
        }
    }
    if (!haveEye) return fail("camera: eye=x,y,z is missing");
    if (!haveTarget) return fail("camera: target=x,y,z is missing");
    if (Status s = validateCamera(cam); !s) return fail(s.error());
    return cam;
}

std::string formatCamera(const Camera& c) {
    auto v = [](const glm::dvec3& p) {
        return exactNumber(p.x) + "," + exactNumber(p.y) + "," + exactNumber(p.z);
    };
    return "eye=" + v(c.eye) + ";target=" + v(c.target) + ";up=" + v(c.up) + ";fov=" + exactNumber(c.fovYDeg);
}

Status validateCamera(const Camera& c) {
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
        return fail("camera: eye, target and up must be finite");
    // Below kMinFovDeg the float projection overflows; below kMinNearPlane reversed-Z depths of
    // ordinary distances become denormal floats and lose their precision.
    if (!std::isfinite(c.fovYDeg) || c.fovYDeg < kMinFovDeg || c.fovYDeg >= 180.0)
        return fail("camera: fov " + exactNumber(c.fovYDeg) + " is outside [" + exactNumber(kMinFovDeg) +
                    ", 180) degrees");
    if (!std::isfinite(c.nearPlane) || c.nearPlane < kMinNearPlane)
        return fail("camera: near plane " + exactNumber(c.nearPlane) + " is below " +
                    exactNumber(kMinNearPlane));
    if (!std::isfinite(c.farPlane) || (c.farPlane != 0.0 && c.farPlane <= c.nearPlane))
        return fail("camera: far plane must be 0 (infinite) or beyond the near plane");
    if (c.nearPlane > kMaxPlaneDistance || c.farPlane > kMaxPlaneDistance)
        return fail("camera: near and far planes must lie within " + exactNumber(kMaxPlaneDistance));
    const glm::dvec3 dir = c.target - c.eye;
    const double len = glm::length(dir);
    if (!(len > 0.0) || !std::isfinite(len)) return fail("camera: eye and target must differ");
    const double upLen = glm::length(c.up);
    if (!(upLen > 0.0) || !std::isfinite(upLen)) return fail("camera: up must not be zero");
    const double s = glm::length(glm::cross(dir / len, c.up / upLen));
    if (!(s > 1e-9)) return fail("camera: up is parallel to the view direction");
    return {};
}

CameraBasis cameraBasis(const Camera& c) {
    CameraBasis b;
    b.back = glm::normalize(c.eye - c.target);
    b.right = glm::normalize(glm::cross(c.up, b.back));
    b.up = glm::cross(b.back, b.right);
    return b;
}

glm::dmat4 viewRotation(const Camera& c) {
    const CameraBasis b = cameraBasis(c);
    glm::dmat4 v(1.0);
    for (int k = 0; k < 3; ++k) {
        v[k][0] = b.right[k];
        v[k][1] = b.up[k];
        v[k][2] = b.back[k];
    }
    return v;
}

glm::dmat4 projection(const Camera& c, double aspect) {
    const double f = 1.0 / std::tan(0.5 * c.fovYDeg * kPi / 180.0);
    const double n = c.nearPlane;
    // depth = (A z + B) / -z: 1 at z = -near, 0 at z = -far (or at infinity).
    double a = 0.0, b = n;
    if (c.farPlane > 0.0) {
        a = n / (c.farPlane - n);
        b = n * c.farPlane / (c.farPlane - n);
    }
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][2] = a;
    p[3][2] = b;
    p[2][3] = -1.0;
    return p;
}

glm::dvec3 pixelDirection(const Camera& c, int width, int height, int i, int j) {
    const CameraBasis b = cameraBasis(c);
    const double t = std::tan(0.5 * c.fovYDeg * kPi / 180.0);
    const double aspect = double(width) / double(height);
    const double x = (2.0 * (double(i) + 0.5) / double(width) - 1.0) * t * aspect;
    const double y = (1.0 - 2.0 * (double(j) + 0.5) / double(height)) * t;
    return glm::normalize(b.right * x + b.up * y - b.back);
}

double nearPlaneRadius(const Camera& c, double aspect) {
    const double t = std::tan(0.5 * c.fovYDeg * kPi / 180.0);
    return c.nearPlane * std::sqrt(1.0 + t * t + t * t * aspect * aspect);
}

} // namespace spatter
