#pragma once
// C++ mirrors of the projector's GLSL blocks in shaders/projector.glsl and forward_data.glsl (the
// decals are DecalBoundsGpu and DecalBodyGpu, GpuLayouts.hpp). Field order, types and padding match the
// std140 / std430 rules; the static_asserts keep both sides in step.

#include <cstdint>
#include <glm/glm.hpp>

namespace spatter::render_detail {

// Binding points of the projector's shaders (layout(binding = N)).
enum ProjectorBinding : uint32_t {
    kProjectorFrameBlock = 0,   // uniform block ProjectorFrame
    kProjectorObjectBuffer = 1, // shader storage ProjectorObjects
    // The decals' bodies and bounds: kDecalBuffer and kDecalBoundsBuffer (GpuLayouts.hpp).
    kProjectorVisibleBuffer = 4,
    kForwardRectBuffer = 0,  // shader storage TileRects of the binning passes (forward_*.comp)
    kForwardCountBuffer = 2, // shader storage TileCounts / TileCursors
    kCullTotalsBuffer = 2,   // shader storage CullTotals of decal.vert (GpuCulling's draw buffer)
};

// std140 uniform block ProjectorFrame.
struct alignas(16) ProjectorFrameGpu {
    glm::mat4 viewProj;      // camera-relative world -> clip
    glm::mat4 view;          // camera-relative world -> view
    glm::mat4 invView;       // view -> camera-relative world
    glm::mat4 invProjection; // clip -> view
    glm::vec4 viewport;      // x, y, 1 / width, 1 / height
    glm::vec4 params;        // x: fade start
};
static_assert(sizeof(ProjectorFrameGpu) == 4 * 64 + 2 * 16, "ProjectorFrameGpu must match ProjectorFrame");

// std430, one per object.
struct alignas(16) ProjectorObjectGpu {
    glm::mat4 model;         // object -> camera-relative world
    glm::mat4 normalMatrix;  // inverse transpose of model's 3x3 part, in the upper left
    glm::mat4 worldToObject; // camera-relative world -> object
    glm::uvec4 info;         // x: object decal ID, y: 1 when model mirrors, z: 1 when it is singular,
                             // w: 1 when the host draws its decals itself
};
static_assert(sizeof(ProjectorObjectGpu) == 208, "ProjectorObjectGpu must match ProjectorObject (std430)");

// std430 SpatterForwardDecal (forward_data.glsl), one per visible decal.
struct alignas(16) ForwardDecalGpu {
    glm::vec4 worldToBox[3];
    glm::vec4 tangent, bitangent, normal, tint;
    glm::uvec4 info;
    glm::vec4 params;
    glm::vec4 axis;
};
static_assert(sizeof(ForwardDecalGpu) == 160, "ForwardDecalGpu must match SpatterForwardDecal (std430)");

// The head of std430 SpatterForwardTiles; the tiles' runs (uvec2 each) follow.
struct alignas(16) ForwardGridGpu {
    glm::ivec4 grid;  // x, y: viewport corner; z: tiles per row; w: rows
    glm::ivec4 info;  // x: tile size; y: 1 with the derivative normal frame; z: decals left out (GPU);
                      // w: the most decals of one tile (GPU)
    glm::vec4 params; // x: fade start
};
static_assert(sizeof(ForwardGridGpu) == 48, "ForwardGridGpu must match SpatterForwardTiles' head");

} // namespace spatter::render_detail
