#pragma once
// KHR_texture_transform: an offset, rotation and scale of the texture coordinates a material samples
// with. spatter's meshes have one UV set and its renderer samples every texture of a material with
// it, so the transform is applied to the UVs of the primitives that use the material when they are
// loaded. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace spatter::gltf {

// The UV transform of material `material` (translation * rotation * scale, as the extension defines
// it): its base colour texture's, else its normal texture's; no value when neither has one. A second,
// different transform on the normal texture, or a texCoord other than 0, is reported in `warning`.
// The error names the material and the field that is not a number or has the wrong length.
Result<std::optional<glm::dmat3>> materialUvTransform(const tinygltf::Model& model, int material,
                                                      std::string& warning);

// Applies `transform` to uvs[begin, end).
void transformUvs(const glm::dmat3& transform, std::vector<glm::vec2>& uvs, size_t begin, size_t end);

// Turns tangents[begin, end) so that each follows the transformed u direction again (the derivative
// of the position by the new u, from the tangent, its bitangent w * cross(normal, tangent) and the
// inverse of the transform), its w the handedness of the new frame. A tangent whose normal is zero,
// or a transform that cannot be inverted, leaves the tangents as they are.
void transformTangents(const glm::dmat3& transform, const std::vector<glm::vec3>& normals,
                       std::vector<glm::vec4>& tangents, size_t begin, size_t end);

} // namespace spatter::gltf
