#include "spatter/core/SampleMemory.hpp"

#include "SharedTriangles.hpp"

namespace spatter {

SampleMemory::TriangleKey SampleMemory::keyOf(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return detail::TriangleCorners::sortedCorners({a, b, c});
}

size_t SampleMemory::Hash::operator()(const TriangleKey& key) const {
    return size_t(detail::TriangleCorners::hashCorners(key));
}

const SampleMemory::Known* SampleMemory::find(const TriangleKey& key) const {
    const auto it = known_.find(key);
    return it != known_.end() ? &it->second : nullptr;
}

void SampleMemory::keep(const TriangleKey& key, const Known& known) {
    const auto [it, added] = known_.try_emplace(key, known);
    if (added || it->second.attained) return;
    if (known.attained || known.farthest < it->second.farthest) it->second = known;
}

} // namespace spatter
