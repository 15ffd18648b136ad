// libFuzzer target: the glTF 2.0 loader (loadGltf), .gltf JSON and .glb alike (told apart by
// content). A loaded scene must pass validateScene and have unit normals; a failure must name the file.

#include "FuzzSupport.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

namespace {

std::string gDir;

bool sceneIsSound(const spatter::Scene& scene) {
    if (!spatter::validateScene(scene)) return false;
    for (const spatter::SceneObject& o : scene.objects) {
        if (o.mesh.normals.size() != o.mesh.positions.size()) return false;
        for (const glm::vec3& n : o.mesh.normals)
            if (!(std::fabs(glm::length(n) - 1.0f) < 1e-3f)) return false;
        if (o.collider && !spatter::validateMesh(*o.collider)) return false;
    }
    return true;
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
    return 0;
}
