#include "HostedWall.hpp"

#include "RenderTestSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstring>

namespace spatter::test {

WallScene::WallScene() : camera(lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0})) {
    scene.objects.push_back(makeSceneObject("wall", makeBox(glm::vec3(3.0f, 2.0f, 0.05f), 2),
                                            glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.0, -0.05))));
    scene.objects.push_back(makeSceneObject("crate", makeBox(glm::vec3(0.3f), 1),
                                            glm::translate(glm::dmat4(1.0), glm::dvec3(0.8, 0.8, 0.5)),
                                            true));
    for (const SceneObject& o : scene.objects)
        transforms.push_back(o.transform);
    DecalType t;
    t.name = "paint";
    t.size = glm::vec2(0.6f);
    t.texture = int(DecalTexture::Paint);
    t.roughness = 0.2f;
    types.push_back(t);
    decals.push_back(decalAt(0, {-0.6f, 0.0f, 0.05f}));
    // Wider than the crate and deep enough to reach the wall behind it: only IDs keep it off the wall.
    Decal onCrate = decalAt(1, {0.0f, 0.0f, 0.3f});
    onCrate.size = glm::vec2(1.0f);
    onCrate.halfDepth = 1.0f;
    decals.push_back(onCrate);
}

Decal WallScene::decalAt(uint32_t object, const glm::vec3& center) {
    Decal d;
    d.object = object;
    d.center = center;
    d.setFrame({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    d.size = glm::vec2(0.6f);
    d.halfDepth = 0.2f;
    d.objectId = object == 1 ? 7 : 0;
    d.opacity = 1.0f;
    return d;
}

std::optional<HostedWall> HostedWall::make(const ProjectorSettings& settings) {
    Result<ForeignHost> host = ForeignHost::create(kWidth, kHeight);
    Result<DecalProjector> projector = DecalProjector::create(settings);
    EXPECT_TRUE(host.ok()) << host.error();
    EXPECT_TRUE(projector.ok()) << projector.error();
    if (!host || !projector) return std::nullopt;
    std::optional<HostedWall> h(
        std::in_place, HostedWall{WallScene(), std::move(host).value(), std::move(projector).value()});
    h->host.setScene(h->wall.scene);
    h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
    EXPECT_TRUE(h->projector.setObjects(h->wall.transforms, h->wall.ids).ok());
    h->projector.setDecalTypes(h->wall.types);
    h->projector.setDecals(h->wall.decals);
    return h;
}

size_t differingPixels(const Image& a, const Image& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); i += 4)
        n += std::memcmp(&a.rgba[i], &b.rgba[i], 4) != 0 ? 1 : 0;
    return n;
}

} // namespace spatter::test
