#pragma once
// CraterClip: a plane that cuts a volumetric decal's crater off where the solid it is carved into
// ends near the hit: the side face at an edge of a crate or a pillar, the back of a thin wall
// (placement finds them in the collision proxy when the decal is spawned). The plane lives in crater
// space, the space of CraterMesh scaled onto the decal (x along the tangent in units of half the
// width, y along the bitangent in units of half the height, z along the normal in units of the
// smaller of the two), so it follows the decal and its object wherever they move. What is kept is
// dot(normal, p) <= offset: `normal` points out of the solid.
//
// Packed into 4 bytes so that a Decal carries two without growing: the unit normal octahedrally
// in two signed bytes, the offset in 1/4096 crater units. packCraterClip rounds towards keeping
// less, the normal's quantisation error included for every point within kCraterClipReach of the
// origin (which holds every crater whose depth bound is at most sqrt(3)), so that a packed plane
// never lets the crater out of the solid.
//
// A volumetric decal has two (CraterClips); the decal system keeps them beside its decals
// (DecalSystem::craterClips) once a crater has one, not in every Decal record.
//
//   CraterClip c = packCraterClip(glm::vec3(1, 0, 0), 0.4f);  // the solid ends at x = 0.4
//   glm::vec4 plane = unpackCraterClip(c);                    // xyz unit normal, w offset

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace spatter {

struct Decal;

constexpr float kCraterClipReach = 2.0f;

struct CraterClip {
    int8_t octX = 0, octY = 0; // octahedral unit normal, in 1/127
    int16_t offset = kNone;    // crater units times 4096; kNone: no plane
    static constexpr int16_t kNone = INT16_MAX;

    bool active() const { return offset != kNone; }
    bool operator==(const CraterClip& o) const {
        return octX == o.octX && octY == o.octY && offset == o.offset;
    }
};

// The clip planes of one volumetric decal; inactive planes keep the whole crater.
struct CraterClips {
    CraterClip planes[2];
    bool any() const { return planes[0].active() || planes[1].active(); }
    bool operator==(const CraterClips& o) const {
        return planes[0] == o.planes[0] && planes[1] == o.planes[1];
    }
};

// The clips of the decal at an index of a decal array, as a renderer asks for them
// (DecalSystem::craterClips); an empty function: no decal has any.
using CraterClipsOf = std::function<CraterClips(size_t index)>;

// The clips of `clips` by index, none past its end. It refers to `clips`: for the call it is given to.
CraterClipsOf craterClipsOf(const std::vector<CraterClips>& clips);

// Crater space of `decal` to the space of its object (the decal's frame scaled by half its width,
// half its height and the smaller of the two, translated to its centre).
glm::dmat4 craterToObject(const Decal& decal);

// The plane dot(normal, p) <= offset (offset in crater units), or an inactive clip when the plane
// keeps the whole crater or when the normal is zero or not finite or the offset not finite.
CraterClip packCraterClip(const glm::vec3& normal, float offset);

// (unit normal, offset), or (0, 0, 0, 1) for an inactive clip, which keeps every point.
glm::vec4 unpackCraterClip(const CraterClip& c);

} // namespace spatter
