#pragma once
// SceneGpu: a Scene's render meshes, materials and textures on the GPU, and what skinning and morphing
// need of it (joint influences and morph target deltas, uploaded once). Object transforms, joint
// matrices and morph weights stay on the CPU in double; the renderer sends them every frame.

#include "GlObjects.hpp"
#include "GpuLayouts.hpp"

#include "spatter/core/Scene.hpp"

#include <cstdint>
#include <vector>

namespace spatter::render_detail {

struct GpuSubmesh {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    uint32_t material = 0; // index into the material buffer (the last entry is the default material)
};

struct GpuMesh {
    GlVertexArray vao;
    GlBuffer vertices;
    GlBuffer indices;
    std::vector<GpuSubmesh> submeshes;
    size_t triangles = 0;
};

class SceneGpu {
public:
    // Uploads `scene` (validated with validateScene first); replaces what was there.
    Status upload(const Scene& scene);

    size_t objectCount() const { return meshOf_.size(); }
    // Object `object`'s mesh; objects placed with the same mesh share one.
    const GpuMesh& mesh(size_t object) const { return meshes_[meshOf_[object]]; }
    GLuint materialBuffer() const { return materialBuffer_.get(); }
    // Textures of material m (0 where it has none).
    GLuint baseColorTexture(uint32_t m) const { return m < baseTextures_.size() ? baseTextures_[m] : 0; }
    GLuint normalTexture(uint32_t m) const { return m < normalTextures_.size() ? normalTextures_[m] : 0; }

    // Skinning and morphing (shaders/pose.glsl): per-object offsets, influences and morph deltas.
    GLuint poseObjectBuffer() const { return poseObjects_.get(); }
    GLuint influenceBuffer() const { return influences_.get(); }
    GLuint morphDeltaBuffer() const { return morphDeltas_.get(); }
    // First entry of skin s in the per-frame joint buffer; jointCount() entries in all.
    uint32_t firstJoint(size_t skin) const { return firstJoint_[skin]; }
    size_t jointCount() const { return jointCount_; }
    // First entry of object o in the per-frame morph weight buffer; weightCount() entries in all.
    uint32_t firstWeight(size_t object) const { return firstWeight_[object]; }
    size_t weightCount() const { return weightCount_; }

private:
    void uploadPose(const Scene& scene);

    std::vector<GpuMesh> meshes_;  // one per distinct mesh
    std::vector<uint32_t> meshOf_; // per object: its mesh in meshes_
    GlBuffer materialBuffer_;
    std::vector<GlTexture> textures_;    // every image uploaded, sRGB and linear as needed
    std::vector<GLuint> baseTextures_;   // per material
    std::vector<GLuint> normalTextures_; // per material
    GlBuffer poseObjects_, influences_, morphDeltas_;
    std::vector<uint32_t> firstJoint_;  // per skin
    std::vector<uint32_t> firstWeight_; // per object
    size_t jointCount_ = 0, weightCount_ = 0;
};

} // namespace spatter::render_detail
