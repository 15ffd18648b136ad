// libFuzzer target: the OBJ, PLY, OFF and STL loader (loadMeshFile, OpenMesh's readers). The first
// byte picks the file extension, the rest is the file. A loaded scene must pass validateScene and
// have unit normals; a failure must name the file.

#include "FuzzSupport.hpp"

#include "spatter/core/SceneLoader.hpp"

#include <cmath>
#include <cstdlib>

namespace {

std::string gDir;
const char* const kExtensions[] = {"obj", "ply", "off", "stl"};

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gDir = spatter::fuzz::workDir("mesh");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string path = gDir + "/input." + kExtensions[data[0] % 4];
    spatter::fuzz::writeFile(path, data + 1, size - 1);
    spatter::Result<spatter::Scene> scene = spatter::loadMeshFile(path);
    if (!scene) {
        if (scene.error().rfind(path + ": ", 0) != 0) std::abort();
        return 0;
    }
    if (!spatter::validateScene(scene.value()) || scene->objects.size() != 1) std::abort();
    const spatter::Mesh& mesh = *scene->objects[0].mesh;
    if (mesh.normals.size() != mesh.positions.size()) std::abort();
    for (const glm::vec3& n : mesh.normals)
        if (!(std::fabs(glm::length(n) - 1.0f) < 1e-3f)) std::abort();
    return 0;
}
