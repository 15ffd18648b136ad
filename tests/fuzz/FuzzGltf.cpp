// libFuzzer target: the glTF 2.0 loader (loadGltf), .gltf JSON and .glb alike (told apart by
// content). A loaded scene must pass validateScene and have unit normals; a failure must name the file.
// A loaded scene is then traced as a game would: its collision world is built (render meshes) and
// shot at every object, with single rays and with a burst (an Embree packet), so that node transforms
// the trace cannot use (TraceTransform.hpp) reach Embree if the world let them through. Its animations
// are posed (SceneEvaluator) and its skinned and morphed meshes deformed, which must never read out
// of bounds.

#include "FuzzSupport.hpp"

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace {

std::string gDir;

bool sceneIsSound(const spatter::Scene& scene) {
    if (!spatter::validateScene(scene)) return false;
    for (const spatter::SceneObject& o : scene.objects) {
        if (o.mesh->normals.size() != o.mesh->positions.size()) return false;
        for (const glm::vec3& n : o.mesh->normals)
            if (!(std::fabs(glm::length(n) - 1.0f) < 1e-3f)) return false;
        if (o.collider && !spatter::validateMesh(*o.collider)) return false;
    }
    return true;
}

// Shoots at the centre of each of the first 16 objects from outside its bounds: one ray, then a burst
// of 8 rays around it in one batch.
void shootAt(const spatter::Scene& scene) {
    spatter::WorldSettings settings;
    settings.useColliders = false;
    spatter::Result<spatter::CollisionWorld> world = spatter::CollisionWorld::build(scene, {}, settings);
    if (!world) std::abort(); // a scene that validates must build
    for (uint32_t i = 0; i < world->objectCount() && i < 16; ++i) {
        const spatter::DBounds b = world->worldBounds(i);
        if (b.empty()) continue;
        const glm::dvec3 target = b.center();
        const glm::dvec3 from = target + glm::dvec3(0.3, 1.0, 0.6) * (b.diagonal() + 1.0);
        std::vector<spatter::Ray> burst;
        for (int k = 0; k < 8; ++k)
            burst.push_back(spatter::Ray{from, target - from + glm::dvec3(0.01 * k, 0.0, -0.01 * k)});
        (void)world->intersect(burst[0]);
        (void)world->intersectBatch(burst);
    }
}

// Poses the first 4 animations at their start, inside and at their end, with the posed positions of
// the first 16 objects at each pose.
void pose(const spatter::Scene& scene) {
    spatter::SceneEvaluator evaluator(scene);
    for (size_t a = 0; a < scene.animation.animations.size() && a < 4; ++a)
        for (double f : {0.0, 0.37, 1.0}) {
            evaluator.evaluate(int(a), f * scene.animation.animations[a].duration);
            for (size_t o = 0; o < scene.objects.size() && o < 16; ++o)
                (void)spatter::posedPositions(scene, o, evaluator);
        }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gDir = spatter::fuzz::workDir("gltf");
    // External files the seed corpus names (images, a buffer), so that such inputs get past loading.
    spatter::fuzz::writeTinyPng(gDir + "/Textures/colormap.png");
    spatter::fuzz::writeTinyPng(gDir + "/DuckCM.png");
    spatter::fuzz::writeTinyPng(gDir + "/image.png");
    std::vector<uint8_t> buffer(4096);
    for (size_t i = 0; i < buffer.size(); ++i)
        buffer[i] = uint8_t(i * 7 + (i >> 8));
    spatter::fuzz::writeFile(gDir + "/buffer.bin", buffer.data(), buffer.size());
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gDir + "/input.gltf";
    spatter::fuzz::writeFile(path, data, size);
    spatter::Result<spatter::Scene> scene = spatter::loadGltf(path);
    if (scene ? !sceneIsSound(scene.value()) : scene.error().rfind(path + ": ", 0) != 0) std::abort();
    if (!scene) return 0;
    shootAt(scene.value());
    pose(scene.value());
    return 0;
}
