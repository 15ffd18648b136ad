#include "spatter/core/ProxyInstances.hpp"

#include "spatter/core/DeformingProxy.hpp"

#include <cstring>
#include <map>
#include <utility>

namespace spatter {

namespace {

bool takesSharedProxy(const SceneObject& o) {
    return o.receivesDecals && !takesDeformingProxy(o);
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameInput(const Mesh& a, const Mesh& b) {
    return sameBits(a.positions, b.positions) && sameBits(a.indices, b.indices);
}

bool sameInput(const SceneObject& a, const SceneObject& b) {
    if (a.collider.has_value() != b.collider.has_value()) return false;
    return (a.mesh == b.mesh || sameInput(*a.mesh, *b.mesh)) &&
           (!a.collider || sameInput(*a.collider, *b.collider));
}

} // namespace

std::vector<size_t> proxySources(const Scene& scene) {
    std::vector<size_t> source(scene.objects.size());
    // The sources so far, by the sizes of their meshes: only meshes of the same sizes are compared.
    std::map<std::pair<size_t, size_t>, std::vector<size_t>> sources;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        source[i] = i;
        if (!takesSharedProxy(o)) continue;
        std::vector<size_t>& same = sources[{o.mesh->positions.size(), o.mesh->indices.size()}];
        for (size_t j : same)
            if (sameInput(o, scene.objects[j])) {
                source[i] = j;
                break;
            }
        if (source[i] == i) same.push_back(i);
    }
    return source;
}

} // namespace spatter
