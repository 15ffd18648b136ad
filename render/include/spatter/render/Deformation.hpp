#pragma once
// Deformation: a vertex animation applied on the GPU in the geometry pass, for dynamic targets that
// bend or wave. Each vertex p (object space, rest pose) moves to
//     p + displacement * amplitude * sin(frequency * dot(waveDirection, p) + phase + speed * t)
// where t is the renderer's time (Renderer::setTime); normals and tangents follow the Jacobian of
// that map. A small frequency times the object's length bends it; a larger one makes it wave.
// Collision proxies and placement see the rest pose; projected decal boxes do not deform (their
// decals slide), texture-space decals do (they are part of the surface).

#include <glm/glm.hpp>

namespace spatter {

struct Deformation {
    float amplitude = 0.0f;                    // object-space units; 0 switches the deformation off
    float frequency = 1.0f;                    // radians per object-space unit along waveDirection
    float phase = 0.0f;                        // radians
    float speed = 0.0f;                        // radians per second of renderer time
    glm::vec3 displacement{0.0f, 0.0f, 1.0f};  // direction vertices move in (normalised on use)
    glm::vec3 waveDirection{1.0f, 0.0f, 0.0f}; // direction the wave runs along (normalised on use)
};

} // namespace spatter
