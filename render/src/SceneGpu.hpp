#pragma once
// SceneGpu: a Scene's render meshes, materials and textures on the GPU. Object transforms stay on
// the CPU in double; the renderer makes them camera-relative every frame.

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

    size_t objectCount() const { return meshes_.size(); }
    const GpuMesh& mesh(size_t object) const { return meshes_[object]; }
    GLuint materialBuffer() const { return materialBuffer_.get(); }
    // Textures of material m (0 where it has none).
    GLuint baseColorTexture(uint32_t m) const { return m < baseTextures_.size() ? baseTextures_[m] : 0; }
    GLuint normalTexture(uint32_t m) const { return m < normalTextures_.size() ? normalTextures_[m] : 0; }

private:
    std::vector<GpuMesh> meshes_;
    GlBuffer materialBuffer_;
    std::vector<GlTexture> textures_;    // every image uploaded, sRGB and linear as needed
    std::vector<GLuint> baseTextures_;   // per material
    std::vector<GLuint> normalTextures_; // per material
};

} // namespace spatter::render_detail
