#pragma once
// Decal: one placed decal, the value that crosses from placement to rendering. Its box is
// |x| <= size.x / 2, |y| <= size.y / 2, |z| <= halfDepth in its frame; the frame and centre are
// stored in the space of the object it lies on, so it follows that object when it moves.
//
// The frame is packed in 64 bits (PackedFrame.hpp): a unit quaternion that turns the box's x, y and z
// axes onto the tangent, the bitangent and the normal, and a mirrored flag that turns the bitangent
// round (the texture drawn mirrored). frame() unpacks it orthonormal and right-handed (left-handed
// when mirrored) to float precision, within kPackedFrameError (4e-6) of an orthonormal frame given to
// setFrame. Each
// decal keeps 28 bytes that three separate axes would spend.
//
// The box is projected along the normal or, slanted, along the shot that placed the decal
// (DecalProjection.hpp): `slant` keeps the axis, and boxToObject() the parallelepiped it makes.
//
//   Decal d;
//   d.setFrame(frameFromNormalAndHint(normal, hint)); // false: no frame can be made of it
//   const Frame f = d.frame();                        // tangent, bitangent, normal

#include "spatter/core/DecalProjection.hpp"
#include "spatter/core/Frame.hpp"
#include "spatter/core/Opacity.hpp"
#include "spatter/core/PackedFrame.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace spatter {

struct Decal {
    glm::vec3 center{0.0f};  // object space
    float halfDepth = 0.05f; // half the projection depth; at least the proxy error bound plus a margin
    uint64_t packedFrame = kIdentityOrientation; // object space (PackedFrame.hpp); kNoOrientation: none
    glm::vec2 size{0.1f};                        // full width and height
    double spawnTime = 0.0;                      // seconds, decal system clock
    uint32_t object = 0;                         // index into Scene::objects
    uint32_t id = 0;                             // 32-bit random decal ID from the seeded generator
    uint16_t type = 0;                           // index of its DecalType in the decal system's registry
    uint8_t objectId = 0; // 8-bit object decal ID: 0 for static geometry, 1..255 for dynamic
    Opacity opacity;      // 1 while alive; falls to 0 while fading out (in steps of 1/255)
    uint32_t slant = 0;   // projection axis relative to the frame (DecalProjection.hpp); 0: the normal

    // The unit quaternion of the frame (the zero quaternion when it has none).
    glm::dquat orientation() const { return unpackOrientation(packedFrame); }
    // Whether the bitangent is -cross(normal, tangent): the texture drawn mirrored.
    bool mirrored() const { return packedMirrored(packedFrame); }
    // Packs a unit quaternion and the mirrored flag (packOrientation).
    void setOrientation(const glm::dquat& unit, bool mirrored) {
        packedFrame = packOrientation(unit, mirrored);
    }

    // The unpacked frame; all three axes zero when the orientation is zero or not finite.
    Frame frame() const;

    // Packs `f`: its normal, its tangent made perpendicular to the normal, and mirrored when the
    // bitangent points against cross(normal, tangent). A frame with a zero, non-finite or parallel
    // normal and tangent has no orientation: it stores kNoOrientation, which renderers reject, and
    // returns false.
    bool setFrame(const Frame& f);

    // The unit projection axis in object space: the normal, slanted by `slant`.
    glm::vec3 projectionAxis() const;
    // Projects the decal along `axis` (object space, pointing out of the surface; need not be unit):
    // sets `slant` from it and the frame, turned to kMaxSlantDeg when farther from the normal. An axis
    // that is zero, not finite or points into the surface projects along the normal.
    void setProjectionAxis(const glm::vec3& axis);

    // Decal box to object space: maps the cube [-1, 1]^3 onto the box (columns: tangent * w/2,
    // bitangent * h/2, the projection axis scaled to reach halfDepth along the normal
    // (normal + slopes.x * tangent + slopes.y * bitangent) * halfDepth, centre).
    glm::mat4 boxToObject() const;
};

// A record of 56 bytes. What only volumetric decals need, their crater's clip planes, lives beside the
// decals (DecalSystem::craterClips) once a crater has them: a world without clipped craters keeps 8 MB
// less a million decals.
static_assert(sizeof(Decal) <= 56, "a Decal record grew past 56 bytes");

} // namespace spatter
