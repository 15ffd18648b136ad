#pragma once
// SampleMemory: what sampledLowerBound (HausdorffBound.hpp) measured toward one surface, triangle by
// triangle, so that a later call toward the same surface from a mesh that keeps some of those triangles
// measures them again only where they could raise its answer. A proxy search's runs keep most of one
// another's triangles (from its third run on, 75% to 97% of them on the shared meshes), and each run
// is judged by such samples against the same render mesh. The answers do not change: a triangle is
// skipped only where none of its samples can lie farther than the largest distance found so far.

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <unordered_map>
#include <vector>

namespace spatter {

class SampleMemory {
public:
    // A triangle's corners, in the order keyOf puts them.
    using TriangleKey = std::array<glm::dvec3, 3>;
    // The key of the triangle with corners a, b, c: the same in any order of the corners.
    static TriangleKey keyOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

    // What is known of a triangle's samples (its centroid and edge midpoints).
    struct Known {
        double farthest = 0.0; // none of them lies farther than this from the surface
        bool attained = false; // and one lies exactly this far
    };

    // What is known of the triangle, or nullptr.
    const Known* find(const TriangleKey& key) const;
    // Keeps what a call learned: an attained distance replaces a bound, a lower bound a higher one.
    void keep(const TriangleKey& key, const Known& known);
    size_t size() const { return known_.size(); }

private:
    struct Hash {
        size_t operator()(const TriangleKey& key) const;
    };
    std::unordered_map<TriangleKey, Known, Hash> known_;
};

} // namespace spatter
