#include "spatter/core/SceneLoader.hpp"

#include "spatter/core/GalleryScene.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace spatter {

static std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

Result<Scene> loadScene(const std::string& source) {
    if (source == "builtin:gallery") {
        Scene scene = makeGalleryScene();
        scene.source = source;
        return scene;
    }
    if (source.rfind("builtin:", 0) == 0)
        return fail(source + ": unknown builtin scene (known: builtin:gallery)");
    const std::string ext = lowerExtension(source);
    Result<Scene> scene = fail(source + ": unsupported file type '" + ext +
                               "' (supported: .gltf .glb .obj .ply .off .stl, or builtin:gallery)");
    if (ext == ".gltf" || ext == ".glb")
        scene = loadGltf(source);
    else if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl")
        scene = loadMeshFile(source);
    if (!scene) return scene;
    if (Status s = validateScene(scene.value()); !s) return fail(source + ": " + s.error());
    scene->source = source;
    return scene;
}

} // namespace spatter
