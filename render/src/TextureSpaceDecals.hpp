#pragma once
// TextureSpaceDecals: the per-object decal textures of texture-space decals (DecalMode.hpp). Each
// enabled object owns an albedo texture (sRGB RGBA8, premultiplied, coverage in alpha), a normal
// texture (RGBA8, the decal normal in the surface's tangent frame, premultiplied) and an R8 UV
// coverage mask rendered once when the object is enabled. Splatting draws the object's mesh into its
// UV layout once per batch (one instanced draw, an instance per decal), then one dilation pass grows
// the UV islands by a texel through a scratch pair shared by all objects of the same size, copied
// back; no render target is created per splat.

#include "DecalBatch.hpp"
#include "SceneGpu.hpp"

#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <map>
#include <memory>
#include <vector>

namespace spatter::render_detail {

class TextureSpaceDecals {
public:
    // Forgets every object's textures (a new scene with `objectCount` objects).
    void reset(size_t objectCount);
    // Creates the object's textures at size x size (cleared; a previous layer is dropped) and renders
    // its UV mask from `mesh`. Fails when a shader does not build.
    Status enable(size_t object, int size, const GpuMesh& mesh);
    void disable(size_t object);
    // Clears the object's decal textures (the mask stays).
    void clear(size_t object);

    bool enabled(size_t object) const { return object < objects_.size() && objects_[object] != nullptr; }
    GLuint albedo(size_t object) const { return enabled(object) ? objects_[object]->albedo.get() : 0; }
    GLuint normal(size_t object) const { return enabled(object) ? objects_[object]->normal.get() : 0; }
    int size(size_t object) const { return enabled(object) ? objects_[object]->size : 0; }
    size_t objectCount() const;
    // GPU memory of every enabled object's textures and mask, plus the dilation scratch textures.
    size_t bytes() const;

    // The GPU copies of a DecalBatch's records and types and of the index lists, bound to the decal,
    // type and visible bindings, and the decal texture arrays. With `posed`, meshes are splatted in
    // the pose of the pose buffers (skinned objects through worldToObject[o]: camera-relative world
    // to object o's space), as the geometry pass draws them; otherwise at rest.
    struct SplatInputs {
        GLuint bounds = 0, bodies = 0, types = 0, lists = 0; // the decals' two parts (DecalRecordBuffers)
        GLuint decalAlbedo = 0, decalNormal = 0;
        bool posed = false;
        std::vector<glm::mat4> worldToObject;
    };

    // Splats the valid instances listed in `perObject[o]` into object o's textures (objects not
    // enabled are skipped), then dilates each object that got one. The caller binds the frame
    // buffers and, when posed, the pose buffers. Returns the decals splatted; counts draws in
    // `drawCalls`.
    Result<size_t> splat(const std::vector<std::vector<uint32_t>>& perObject, const SceneGpu& scene,
                         const SplatInputs& in, float fadeStart, size_t& drawCalls);

private:
    struct Layer {
        int size = 0;
        GlTexture albedo, normal, mask;
        GlFramebuffer framebuffer, maskFramebuffer;
    };
    struct Scratch {
        GlTexture albedo, normal;
        GlFramebuffer framebuffer;
    };
    Status buildPrograms();
    Scratch& scratch(int size);
    void dilate(Layer& layer, size_t& drawCalls);

    std::vector<std::unique_ptr<Layer>> objects_;
    std::map<int, Scratch> scratch_;
    GlProgram maskProgram_, splatProgram_, dilateProgram_;
    GlVertexArray emptyVao_;
};

} // namespace spatter::render_detail
