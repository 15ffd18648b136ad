// spatter-info SCENE: prints one JSON object describing a scene (objects, triangles, bounds,
// animations, skins, morph targets).

#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <string>

static const char* kUsage = R"(usage: spatter-info SCENE

Loads SCENE and prints one JSON object on stdout:
  {"objects": N, "meshes": M, "triangles": T, "dynamic_objects": D,
   "bounds": {"min": [x,y,z], "max": [x,y,z]},
   "animations": [{"name", "duration", "channels"}], "skins": [{"name", "joints"}],
   "extensions_used": [...], "extensions_required": [...],
   "objects_detail": [{"name", "triangles", "dynamic", "receives_decals", "has_collider",
                       "traced", "instanced", "collision_mesh_of", "skin", "morph_targets"}]}
meshes counts the render meshes the scene keeps: the objects placed with one mesh (every node and
instance of a glTF mesh) share it. Bounds are world-space, over every render mesh, in the rest pose.
duration is in seconds; skin is the index into "skins" of the object's skin, or null; morph_targets
counts the object's morph targets; the extensions are the glTF file's lists (empty for other
formats). An object that an animation moves or deforms is dynamic. traced is whether shots can hit
the object: it receives decals and its transform is one single-precision ray tracing can use (finite
inverse, condition number at most 65536, scales within 2^-25..2^25, within 2^32 of the world's
centre, not smaller than a few float steps there). For each receiver that is not traced a warning on
stderr names it and says why. instanced is whether the collision world traces the object as an
instance of an object-space scene (dynamic objects, and static ones whose mesh it holds four times
or more) rather than in its static scene; collision_mesh_of is the index of the object whose
collision mesh it uses: an earlier object placed with the same mesh and authored collider, or its
own index.

SCENE is builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file.
On a scene that cannot be loaded or traced: a one-line error on stderr and exit code 1; on bad
usage (no scene, more than one, or an option other than --help), exit code 2.
)";

int main(int argc, char** argv) {
    if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (argc != 2) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    if (argv[1][0] == '-' && argv[1][1] != '\0') {
        std::cerr << "spatter-info: unknown option " << argv[1] << "\n(see spatter-info --help)\n";
        return 2;
    }
    spatter::Result<spatter::Scene> scene = spatter::loadScene(argv[1]);
    if (!scene) {
        std::cerr << "spatter-info: " << scene.error() << "\n";
        return 1;
    }
    for (const std::string& w : scene->warnings)
        std::cerr << "spatter-info: warning: " << w << "\n";
    spatter::WorldSettings worldSettings;
    worldSettings.useColliders = false; // only the transforms matter here
    spatter::Result<spatter::CollisionWorld> world =
        spatter::CollisionWorld::build(scene.value(), {}, worldSettings);
    if (!world) {
        std::cerr << "spatter-info: " << world.error() << "\n";
        return 1;
    }
    for (const std::string& warning : world->warnings())
        std::cerr << "spatter-info: warning: " << warning << "\n";
    const spatter::DBounds b = scene->worldBounds();
    nlohmann::ordered_json out;
    out["objects"] = scene->objects.size();
    out["meshes"] = scene->meshCount();
    out["triangles"] = scene->triangleCount();
    out["dynamic_objects"] = scene->dynamicObjectCount();
    out["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
    out["animations"] = nlohmann::ordered_json::array();
    for (const spatter::Animation& a : scene->animation.animations)
        out["animations"].push_back(
            {{"name", a.name}, {"duration", a.duration}, {"channels", a.channels.size()}});
    out["skins"] = nlohmann::ordered_json::array();
    for (const spatter::Skin& s : scene->animation.skins)
        out["skins"].push_back({{"name", s.name}, {"joints", s.joints.size()}});
    out["extensions_used"] = scene->extensionsUsed;
    out["extensions_required"] = scene->extensionsRequired;
    nlohmann::ordered_json detail = nlohmann::ordered_json::array();
    for (uint32_t i = 0; i < scene->objects.size(); ++i) {
        const spatter::SceneObject& o = scene->objects[i];
        detail.push_back({{"name", o.name},
                          {"triangles", o.mesh->triangleCount()},
                          {"dynamic", o.dynamic},
                          {"receives_decals", o.receivesDecals},
                          {"has_collider", o.collider.has_value()},
                          {"traced", world->object(i)->traced},
                          {"instanced", world->object(i)->instanced},
                          {"collision_mesh_of", world->object(i)->collisionMeshOf},
                          {"skin", o.skin == -1 ? nlohmann::ordered_json() : nlohmann::ordered_json(o.skin)},
                          {"morph_targets", o.morphTargets.size()}});
    }
    out["objects_detail"] = std::move(detail);
    std::cout << out.dump() << "\n";
    return 0;
}
