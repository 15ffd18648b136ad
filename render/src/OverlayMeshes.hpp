#pragma once
// OverlayMeshes: per-object wireframes (the collision proxies) as one line buffer on the GPU. Each
// mesh is welded by exact position and reduced to its unique edges once, when it is set; a frame
// draws all of them with one glDrawElements(GL_LINES), every vertex carrying its object index so the
// vertex shader applies that object's current transform.

#include "GlObjects.hpp"

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

// The unique edges of `mesh` after welding vertices with identical positions, as pairs of indices
// into `positions` (the welded vertices that some edge uses). Degenerate edges are dropped.
// Precondition: validateMesh(mesh) succeeds.
struct EdgeList {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> lines; // two indices per edge
};
EdgeList uniqueEdges(const Mesh& mesh);

class OverlayMeshes {
public:
    // Replaces the wireframes: one mesh per scene object (`objectCount` of them; an empty mesh draws
    // nothing), or none at all. Fails, keeping the previous ones, on a count mismatch or a mesh
    // that validateMesh rejects (the error names the object).
    Status set(const std::vector<Mesh>& meshes, size_t objectCount);
    void clear();

    size_t lineCount() const { return indexCount_ / 2; }
    GLuint vertexArray() const { return vao_.get(); }
    size_t indexCount() const { return indexCount_; }

private:
    GlVertexArray vao_;
    GlBuffer vertices_;
    GlBuffer indices_;
    size_t indexCount_ = 0;
};

} // namespace spatter::render_detail
