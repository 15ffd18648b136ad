#include "InstanceMemory.hpp"

#include "spatter/core/ProcessMemory.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

namespace spatter::bench {

namespace {

// `copies` static objects in a row, each placed with `mesh`.
Scene placed(const std::shared_ptr<const Mesh>& mesh, size_t copies, bool shared) {
    Scene s;
    s.source = "instances";
    const double step = 1.5 * double(mesh->bounds().diagonal());
    for (size_t i = 0; i < copies; ++i) {
        glm::dmat4 at(1.0);
        at[3] = glm::dvec4(step * double(i), 0.0, 0.0, 1.0);
        s.objects.push_back(
            makeSceneObject("copy_" + std::to_string(i), shared ? mesh : shareMesh(*mesh), at));
    }
    return s;
}

// The C heap that making `value` takes, and the value.
template <class Make> auto measured(Make&& make, size_t& bytes) {
    const size_t before = heapBytes();
    auto value = make();
    bytes = heapBytes() - before;
    return value;
}

} // namespace

Json instanceMemory(const Mesh& mesh, const Proxy& proxy, size_t copies) {
    size_t sceneShared = 0, sceneCopied = 0, proxiesShared = 0, proxiesCopied = 0, world = 0;
    const Scene shared = measured([&] { return placed(shareMesh(mesh), copies, true); }, sceneShared);
    const Scene copied = measured([&] { return placed(shared.objects[0].mesh, copies, false); }, sceneCopied);
    using Proxies = std::vector<std::shared_ptr<const Proxy>>;
    const Proxies handed = measured([&] { return Proxies(copies, shareProxy(proxy)); }, proxiesShared);
    const Proxies each = measured(
        [&] {
            Proxies out;
            for (size_t i = 0; i < copies; ++i)
                out.push_back(shareProxy(proxy));
            return out;
        },
        proxiesCopied);
    const std::optional<CollisionWorld> w = measured(
        [&] {
            Result<CollisionWorld> built = CollisionWorld::build(shared, handed);
            return built ? std::optional<CollisionWorld>(std::move(built).value()) : std::nullopt;
        },
        world);
    auto kb = [](size_t bytes) { return double(bytes) / 1024.0; };
    std::printf("\nplaced %zu times (static, each with the proxy):\n", copies);
    std::printf("  scene                 %10.1f KB with one mesh, %10.1f KB with a copy each (%.0fx)\n",
                kb(sceneShared), kb(sceneCopied), double(sceneCopied) / double(sceneShared));
    std::printf("  proxy list            %10.1f KB with one proxy, %9.1f KB with a copy each (%.0fx)\n",
                kb(proxiesShared), kb(proxiesCopied), double(proxiesCopied) / double(proxiesShared));
    if (w) std::printf("  collision world       %10.1f KB (one instanced scene for the copies)\n", kb(world));
    Json j;
    j["copies"] = copies;
    j["scene_shared_bytes"] = sceneShared;
    j["scene_copied_bytes"] = sceneCopied;
    j["proxies_shared_bytes"] = proxiesShared;
    j["proxies_copied_bytes"] = proxiesCopied;
    if (w) j["world_bytes"] = world;
    return j;
}

} // namespace spatter::bench
