#pragma once
// Camera: a perspective camera in world space (double precision), its reversed-Z projection, and
// the ray through a pixel, which is what the renderer's pixel (i, j) shows.
//
// Conventions:
// - View space is right-handed: the camera looks down -Z, +Y is up on screen, +X right.
// - The projection is reversed-Z for a [0, 1] depth range (glClipControl(GL_LOWER_LEFT,
//   GL_ZERO_TO_ONE)): depth 1 at the near plane, falling towards 0 with distance; with
//   farPlane == 0 the far plane is at infinity (depth 0 there).
// - The GPU sees the world relative to the eye: the view matrix is a rotation only, and object
//   transforms have the eye subtracted in double before they are converted to float.
// - Pixel (i, j) of a width x height image, j counted from the top row, shows the ray through its
//   centre, normalised device coordinates x = 2 (i + 0.5) / width - 1, y = 1 - 2 (j + 0.5) / height.

#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>
#include <string>

namespace spatter {

struct Camera {
    glm::dvec3 eye{0.0, 1.6, 6.0};
    glm::dvec3 target{0.0, 1.2, 0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovYDeg = 60.0;   // vertical field of view, degrees, in (0, 180)
    double nearPlane = 0.05; // distance to the near plane, > 0
    double farPlane = 0.0;   // distance to the far plane; 0 = infinitely far
};

// Parses "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG". Keys may come in any order and each at most once;
// eye and target are required, up defaults to +Y and fov to 60. Spaces around items are allowed.
// Errors name the item (unknown key, missing value, not a number) and the checks of validateCamera.
Result<Camera> parseCamera(const std::string& text);

// The camera as parseCamera reads it.
std::string formatCamera(const Camera& camera);

// Smallest field of view and near plane validateCamera accepts, and the farthest near or far plane
// (the float projection holds them).
constexpr double kMinFovDeg = 1e-3;
constexpr double kMinNearPlane = 1e-6;
constexpr double kMaxPlaneDistance = 1e15;

// Fails when a value is not finite, eye equals target, up is zero or parallel to the view
// direction, the field of view is outside [kMinFovDeg, 180), the near plane is below
// kMinNearPlane, a far plane is set (non-zero) but not beyond the near plane, or either plane lies
// beyond kMaxPlaneDistance.
Status validateCamera(const Camera& camera);

// Unit axes of the camera in world space: right (+X), up (+Y) and back (+Z; the view direction
// is -back). Precondition: validateCamera(camera) succeeds.
struct CameraBasis {
    glm::dvec3 right{1, 0, 0};
    glm::dvec3 up{0, 1, 0};
    glm::dvec3 back{0, 0, 1};
};
CameraBasis cameraBasis(const Camera& camera);

// World (relative to the eye) to view space: the rotation of cameraBasis, no translation.
glm::dmat4 viewRotation(const Camera& camera);

// The reversed-Z projection for an aspect ratio width / height.
glm::dmat4 projection(const Camera& camera, double aspect);

// Unit world-space direction of the ray from the eye through the centre of pixel (i, j), j from
// the top row, of a width x height image.
glm::dvec3 pixelDirection(const Camera& camera, int width, int height, int i, int j);

// Radius of a sphere around the eye that contains the part of the near plane inside the view
// (its rectangle); a box that crosses the near plane in view always touches this sphere.
double nearPlaneRadius(const Camera& camera, double aspect);

} // namespace spatter
