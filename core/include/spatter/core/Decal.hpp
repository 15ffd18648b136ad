#pragma once
// Decal: one placed decal, the value that crosses from placement to rendering. Its box is
// |x| <= size.x / 2, |y| <= size.y / 2, |z| <= halfDepth in its frame; the frame and centre are
// stored in the space of the object it lies on, so it follows that object when it moves.

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Frame.hpp"

#include <cstdint>
#include <glm/glm.hpp>

namespace spatter {

struct Decal {
    Frame frame;             // object space; normal points out of the surface, towards the shooter
    glm::vec3 center{0.0f};  // object space
    glm::vec2 size{0.1f};    // full width and height
    float halfDepth = 0.05f; // half the projection depth; at least the proxy error bound plus a margin
    uint32_t object = 0;     // index into Scene::objects
    uint32_t id = 0;         // 32-bit random decal ID from the seeded generator
    uint16_t type = 0;       // index of its DecalType in the decal system's registry
    uint8_t objectId = 0;    // 8-bit object decal ID: 0 for static geometry, 1..255 for dynamic
    double spawnTime = 0.0;  // seconds, decal system clock
    float opacity = 1.0f;    // 1 while alive; falls to 0 while fading out
    CraterClip clips[2];     // volumetric decals: where the solid ends around the crater (CraterClip.hpp)

    // Decal box to object space: maps the cube [-1, 1]^3 onto the box (columns: tangent * w/2,
    // bitangent * h/2, normal * halfDepth, centre).
    glm::mat4 boxToObject() const {
        return glm::mat4(glm::vec4(frame.tangent * (size.x * 0.5f), 0.0f),
                         glm::vec4(frame.bitangent * (size.y * 0.5f), 0.0f),
                         glm::vec4(frame.normal * halfDepth, 0.0f), glm::vec4(center, 1.0f));
    }
};

// Two records fit a cache line: the clip planes live in what would otherwise be padding.
static_assert(sizeof(Decal) <= 96, "a Decal record grew past 96 bytes");

} // namespace spatter
