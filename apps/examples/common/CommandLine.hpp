#pragma once
// The command line of spatter's example hosts, with the options of spatter-render and their
// meanings:
//   SCENE (--decals FILE.jsonl | --rays FILE) [--camera "eye=..;target=..;up=..;fov=.."]
//         [--size WxH] [--view final|albedo|coverage] [--out FILE.png] [--help]
// and a program's own switches (spatter-example-deferred's --dbuffer); what it names, loaded: the
// scene, its decals and the camera; and the exit codes. Written against spatter's installed headers
// only.

#include <spatter/core/Result.hpp>
#include <spatter/core/Scene.hpp>
#include <spatter/placement/DecalRecords.hpp>
#include <spatter/render/Camera.hpp>

#include <glm/glm.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace example {

enum class View {
    Final,    // lit by the host's own lighting pass
    Albedo,   // the host's albedo after the decals, sRGB-encoded
    Coverage, // white where at least one decal changes the pixel, black elsewhere
};

// A switch (an option without a value) of one program's own, such as "--dbuffer".
struct Switch {
    std::string name;
    std::string help; // for the usage text: lines of at most 80 characters
};

struct Options {
    std::string scene;                     // builtin:gallery or a scene file
    std::string decals;                    // spatter-place output (JSON Lines); empty: none
    std::string rays;                      // a ray file placed through the decal system; empty: none
    std::optional<spatter::Camera> camera; // --camera; none: the default view of the scene
    int width = 960, height = 540;
    View view = View::Final;
    std::string out = "render.png";
    std::set<std::string> switches; // the program's own switches given
    bool help = false;              // --help: print the usage and do nothing else
};

// The options in argv[1..argc), taking `own` switches besides spatter-render's options. Fails with a
// message that names the option at fault: an unknown option, one given twice, a missing value (or
// one that starts with "--") or a bad one, no scene or two, --decals with --rays.
spatter::Result<Options> parseCommandLine(int argc, char** argv, const std::vector<Switch>& own = {});

// The usage text of `program`, after a paragraph of `description`, with its `own` switches.
std::string usage(const std::string& program, const std::string& description,
                  const std::vector<Switch>& own = {});

// The exit codes of spatter-render: prints "program: message" to stderr and returns 2 (bad options,
// with a pointer to --help) or 1 (the scene, the decals or the GL context failed).
int usageError(const std::string& program, const std::string& message);
int failure(const std::string& program, const std::string& message);

struct Inputs {
    spatter::Scene scene;
    spatter::LoadedDecals decals; // empty without --decals and --rays
    spatter::Camera camera;       // its near plane set for the scene (see loadInputs)
    glm::dmat4 view{1.0};         // world to view space, double
    glm::dmat4 projection{1.0};   // view to clip space: standard Z, GL's default [-1, 1] clip depth
};

// Loads the scene and the decals the options name and settles the camera: the one given, or
// spatter-render's default view (the centre of the scene's bounds seen from the front, above). The
// near plane is a thousandth of the scene's diagonal, ten times spatter-render's: the examples'
// 24-bit depth buffers keep their precision by it (only what lies nearer to the eye than that is
// drawn differently). The far plane lies at twice the distance to the farthest corner of the
// scene's bounds, so that a decal box that holds the eye keeps its far faces.
// Decals take spatter-render's defaults: the bullet_hole look, decals of 2% of the scene's bounding
// diagonal (decalSizeForScene) within 80 degrees and seed 1 for rays. Fails on a scene or decal file that
// cannot be used, with its loader's message.
spatter::Result<Inputs> loadInputs(const Options& options);

} // namespace example
