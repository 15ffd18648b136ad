#pragma once
// C++ mirrors of the GLSL blocks in shaders/common.glsl. Field order, types and padding match the
// std140 / std430 rules; the static_asserts keep both sides in step.

#include <cstdint>
#include <glm/glm.hpp>

namespace spatter::render_detail {

// Buffer binding points (layout(binding = N) in the shaders).
enum Binding : uint32_t {
    kFrameBlock = 0,   // uniform block FrameBlock
    kObjectBuffer = 1, // shader storage ObjectBuffer
    kMaterialBuffer = 2,
    kDecalBuffer = 3,
    kVisibleBuffer = 4,
    kDecalTypeBuffer = 8,
    kDecalBoundsBuffer = 9,
};

// Decal flags (DecalTypeGpu::info.y; kDecalMirrored from DecalRecordGpu::frame; kDecalSlanted, which
// only the shaders read, from its slant), as SPATTER_DECAL_* in shaders/decal_flags.glsl.
enum DecalFlag : uint32_t {
    kDecalWrap = 1u,
    kDecalNormalMap = 2u,
    kDecalFadeLinear = 4u,
    kDecalFadeSmooth = 8u,
    kDecalRoughness = 16u,
    kDecalMirrored = 32u,
    kDecalSlanted = 64u,
};

// std140 uniform block, binding kFrameBlock.
struct alignas(16) FrameGpu {
    glm::mat4 viewProj;       // camera-relative world -> clip
    glm::mat4 view;           // camera-relative world -> view (a rotation)
    glm::mat4 invView;        // view -> camera-relative world
    glm::vec4 projection;     // x = P[0][0], y = P[1][1], z = A, w = B: depth = (A z + B) / -z
    glm::vec4 viewport;       // width, height, 1 / width, 1 / height
    glm::vec4 lightDirection; // xyz: unit, towards the light; w: intensity
    glm::vec4 lightColor;     // rgb; w: exposure
    glm::vec4 skyAmbient;     // rgb
    glm::vec4 groundAmbient;  // rgb
    glm::vec4 depthRange;     // x: nearest, y: farthest scene distance (depth view); z: decal fade start
};
static_assert(sizeof(FrameGpu) == 3 * 64 + 7 * 16, "FrameGpu must match FrameBlock (std140)");

// std430, binding kObjectBuffer, one per scene object.
struct alignas(16) ObjectGpu {
    glm::mat4 model;        // object -> camera-relative world
    glm::mat4 normalMatrix; // inverse transpose of model's 3x3 part, in the upper left
    glm::uvec4 info;        // x: object decal ID, y: 1 when model mirrors (negative determinant),
                            // z: 1 when the object has a texture-space decal layer
    glm::vec4 deformA;      // xyz: displacement direction * amplitude (0: no deformation); w: frequency
    glm::vec4 deformB;      // xyz: unit wave direction; w: phase at this frame's time
};
static_assert(sizeof(ObjectGpu) == 176, "ObjectGpu must match ObjectData (std430)");

// std430, binding kMaterialBuffer; the last entry is the default material.
struct alignas(16) MaterialGpu {
    glm::vec4 baseColor;
    glm::vec4 params; // x: roughness, y: metallic, z: normal scale
    glm::uvec4 flags; // x: has base colour texture, y: has normal texture
};
static_assert(sizeof(MaterialGpu) == 48, "MaterialGpu must match MaterialData (std430)");

// One decal as the CPU builds it (DecalRecord.hpp). Object-space data only, so it changes only when
// the decal does; the camera-relative world-to-box transform is composed in the shaders with the
// object's, and the rest of the decal's look comes from its type (DecalTypeGpu). The GPU keeps it in
// two parts (DecalBoundsGpu, DecalBodyGpu: decal_data.glsl).
struct alignas(16) DecalRecordGpu {
    glm::vec4 centerDepth; // xyz: the box's centre in object space; w: its half depth (0: not drawable)
    glm::uvec2 frame;      // Decal::packedFrame (PackedFrame.hpp): x its low 32 bits, y its high ones
    glm::vec2 halfSize;    // half the width and height
    glm::uvec4 info;       // x: object index; y: type (bits 0-15), opacity in 1/255 (24-31); z: slant
                           // (DecalProjection.hpp); w: 0. Mirrored: bit 62 of the frame. A decal
                           // clips to its object's decal ID (ProjectorObjectGpu), not its own
};
static_assert(sizeof(DecalRecordGpu) == 48, "DecalRecordGpu is three vec4s");

// std430, binding kDecalBoundsBuffer: what the culling's pass over every decal reads (DecalBounds).
struct alignas(16) DecalBoundsGpu {
    glm::vec3 center;      // the box's centre in object space
    uint32_t objectRadius; // bits 16-30: bounding radius (a positive float's high half without its
                           // sign, rounded up; 0: not drawable); bit 31: the object index is past 16
                           // bits (kBoundsWideObject); bits 0-15: the object index's low 16 bits
};
static_assert(sizeof(DecalBoundsGpu) == 16, "DecalBoundsGpu must match DecalBounds (std430)");
// DecalBoundsGpu::objectRadius's bit telling that the object index has bits past the low 16, so that a
// culling which reads only those (at most 65,536 objects) takes such a decal's object for unknown
// instead of another one.
constexpr uint32_t kBoundsWideObject = 0x80000000u;

// std430, binding kDecalBuffer: the rest of a decal (DecalBody). Scalars only, so that the array's
// stride is 28 bytes (a vector member would align the struct, and its stride, to 8 or 16).
struct DecalBodyGpu {
    uint32_t frame[2]; // Decal::packedFrame: its low 32 bits, its high ones
    float halfSize[2];
    float halfDepth;
    uint32_t look; // type (bits 0-15), object index bits 16-23 (16-23), opacity in 1/255 (24-31)
    uint32_t slant;
};
static_assert(sizeof(DecalBodyGpu) == 28, "DecalBodyGpu must match DecalBody (std430)");

// The most objects a projector takes: a decal's object index is 24 bits on the GPU (DecalBodyGpu),
// and the largest such value names no object (a decal whose object index does not fit is kept with
// it, and not drawn).
constexpr uint32_t kMaxProjectorObjects = (1u << 24) - 1;

// std430, binding kDecalTypeBuffer: one per decal type (DecalTypeRecord in decal_data.glsl).
struct alignas(16) DecalTypeGpu {
    glm::vec4 tint;   // rgb; a: alpha
    glm::uvec4 info;  // x: texture layer; y: DecalFlag bits; z: 1 when decals of the type can be drawn,
                      // 2 when the host draws them itself (DecalProjector::setHostDrawn), 0 otherwise;
                      // w: the layer's cutout (DecalCutout.hpp, packCutout)
    glm::vec4 params; // x: cosine of the largest accepted angle; y: roughness written
};
static_assert(sizeof(DecalTypeGpu) == 48, "DecalTypeGpu must match DecalTypeRecord (std430)");

// Binding points of the geometry pass's skinning and morphing buffers (shaders/pose.glsl).
enum PoseBinding : uint32_t {
    kPoseObjectBuffer = 10, // PoseObjectGpu per object, uploaded with the scene
    kInfluenceBuffer = 11,  // InfluenceGpu per vertex and influence, uploaded with the scene
    kMorphDeltaBuffer = 12, // vec4 (position, normal, tangent delta) per target and vertex, with the scene
    kJointBuffer = 13,      // mat4 per skin joint, camera-relative, every frame
    kMorphWeightBuffer = 14 // float per object morph target, every frame
};

// std430, binding kPoseObjectBuffer: where an object's skin and morph data start.
struct alignas(16) PoseObjectGpu {
    glm::uvec4 skin;  // x: first influence; y: influences per vertex (0: not skinned); z: first joint
    glm::uvec4 morph; // x: first delta (three per target and vertex); y: targets; z: first weight;
                      // w: vertices
};
static_assert(sizeof(PoseObjectGpu) == 32, "PoseObjectGpu must match PoseObject (std430)");

// std430, binding kInfluenceBuffer: one joint influence of a vertex.
struct InfluenceGpu {
    uint32_t joint; // index into the object's skin joints
    float weight;
};
static_assert(sizeof(InfluenceGpu) == 8, "InfluenceGpu must match Influence (std430)");

} // namespace spatter::render_detail
