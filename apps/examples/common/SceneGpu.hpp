#pragma once
// The scene as spatter's example hosts draw it: each object's mesh on the GPU (positions, normals,
// and its parts with their materials' base colour and roughness factors), with its object-to-world
// transform in double and its 8-bit decal ID as the projector takes them; the vertex stage that
// draws the objects relative to the eye; and the draw of every object.
//
// The objects that take no decals are drawn with the others, with an object decal ID that no decal
// has: the projector keeps every decal to the pixels of its own object's ID, so none shows on them.

#include "CommandLine.hpp"

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace example {

// The vertex stage of the scene (a #version line and all), to link with a host's fragment stage. It
// passes on v_normal (world space, not normalised) and v_position (the point relative to the eye, in
// world space). drawScene sets these uniforms, by location, for it and for the fragment stage:
//   0  mat4 u_modelViewProj  object to clip space
//   4  mat4 u_model          object to eye-relative world space
//   8  mat3 u_normalMatrix   object to world space, for normals
//   11 vec4 u_material       linear base colour (RGB) and roughness (A) of the part drawn
//   12 uint u_decalId        the object's decal ID
//   13 bool u_mirrored       the object's transform flips the winding: the surfaces are two-sided,
//                            and a back face (gl_FrontFacing == u_mirrored) shows the reversed normal
extern const char* const kSceneVertex;

// Consecutive indices of an object drawn with one material.
struct DrawRange {
    GLsizei first = 0, count = 0;
    glm::vec4 material{1.0f}; // linear base colour, roughness
};

struct ObjectGpu {
    GLuint vertexArray = 0; // 0: the object has no triangles
    std::vector<DrawRange> ranges;
};

struct SceneGpu {
    std::vector<ObjectGpu> objects;
    std::vector<glm::dmat4> transforms; // object to world, one per object (DecalProjector::setObjects)
    std::vector<uint8_t> decalIds;      // one per object (DecalProjector::setObjects)
};

// The scene of `in` on the GPU. The decal IDs are those the decals were loaded with; the objects that
// take no decals get the smallest ID no decal has. Fails when the decals use all 256 IDs and an
// object takes no decals.
spatter::Result<SceneGpu> uploadScene(const Inputs& in);

// Draws every object with its uniforms (see kSceneVertex) through the current program into the
// current framebuffer, with the GL state the caller set.
void drawScene(const SceneGpu& scene, const Inputs& in);

} // namespace example
