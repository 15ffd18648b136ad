#pragma once
// GltfReference: an independent reading of a .glb file for reference values in the animation tests.
// It shares nothing with spatter's loader or evaluator: its own GLB and accessor reading, its own
// node walk, key search (linear), interpolation (glm::slerp for rotations), morphing and skinning,
// all in double straight from the file's numbers.

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace spatter::test {

class GltfReference {
public:
    // Reads `glbPath`; ok() is false when the file is not a GLB with a JSON and a binary chunk.
    explicit GltfReference(const std::string& glbPath);
    bool ok() const { return !doc_.is_null(); }

    // World transform of node `node` at time `t` of animation `animation` (-1: the rest pose).
    glm::dmat4 nodeWorld(int node, int animation, double t) const;

    // Morph weights of node `node` at time `t` (empty when its mesh has no targets).
    std::vector<double> morphWeights(int node, int animation, double t) const;

    // World positions of every vertex of node `node`'s mesh (its primitives in order) at time `t`:
    // morphed, then skinned when the node has a skin, else placed by the node's world transform.
    std::vector<glm::dvec3> worldPositions(int node, int animation, double t) const;

private:
    std::vector<double> read(int accessor) const; // every component of every element, in order
    void localTrs(int node, int animation, double t, glm::dvec3& tr, glm::dquat& r, glm::dvec3& s) const;
    std::vector<double> sampleChannel(const nlohmann::json& sampler, int width, double t,
                                      bool rotation) const;
    int parentOf(int node) const;

    nlohmann::json doc_;
    std::vector<uint8_t> bin_;
};

} // namespace spatter::test
