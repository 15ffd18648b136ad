// spatter-bench COMMAND [ARGS...]: benchmarks and reports. Each command is one entry of kCommands;
// adding one is adding its entry (and its file).

#include "CharacterBench.hpp"
#include "LoadBench.hpp"
#include "Memory.hpp"
#include "PersistenceBench.hpp"
#include "PlacementBench.hpp"
#include "PoseBench.hpp"
#include "ProxyBench.hpp"
#include "RenderBench.hpp"
#include "SkinnedBench.hpp"
#include "SkipBench.hpp"
#include "StressReport.hpp"
#include "SurfaceBench.hpp"
#include "Tradeoff.hpp"
#include "VolumetricBench.hpp"

#include <cstdio>
#include <cstring>

namespace {

struct Command {
    const char* name;
    const char* summary;
    int (*run)(int argc, char** argv); // argv[0] is the command's name
};

const Command kCommands[] = {
    {"stress", "numerical stress cases at full size: a report table (--json FILE for the numbers)",
     spatter::bench::runStressCommand},
    {"placement", "spawn and spawnBatch against raw Embree on the same proxy and rays (--json FILE)",
     spatter::bench::runPlacementCommand},
    {"tradeoff", "run time against error: render mesh and proxies per backend and tolerance, three.js peer",
     spatter::bench::runTradeoffCommand},
    {"render", "GPU time of the decal pass: count, visible fraction, coverage, resolution, features",
     spatter::bench::runRenderCommand},
    {"memory", "bytes per decal (CPU, GPU) and per object (proxy, BVH, decal textures)",
     spatter::bench::runMemoryCommand},
    {"skip", "what each skip of the design saves: on against forced off, in one run",
     spatter::bench::runSkipCommand},
    {"proxy", "certified proxies against plain meshoptimizer: triangles and time per mesh and tolerance",
     spatter::bench::runProxyCommand},
    {"volumetric", "GPU time of volumetric decals against flat ones, 1 to 4096 in view (--json FILE)",
     spatter::bench::runVolumetricCommand},
    {"persistence", "saving and loading a decal system: time and MB/s, bytes per decal (--json FILE)",
     spatter::bench::runPersistenceCommand},
    {"pose", "posing an animated scene per frame on one core: evaluation, posed positions (--json FILE)",
     spatter::bench::runPoseCommand},
    {"load", "loading a Draco-compressed glTF against its uncompressed twin: the time ratio (--json FILE)",
     spatter::bench::runLoadCommand},
    {"skinned",
     "decals on skinned objects: pose update, spawn against static, drift over a cycle (--json FILE)",
     spatter::bench::runSkinnedCommand},
    {"characters", "the frame cost of decals on animated characters against none (GPU, --json FILE)",
     spatter::bench::runCharactersCommand},
    {"surface", "searching the drawn surface along decals' axis lines: time against the frame (--json FILE)",
     spatter::bench::runSurfaceCommand},
};

void usage(std::FILE* out) {
    std::fprintf(out, "usage: spatter-bench COMMAND [ARGS...]\n\ncommands:\n");
    for (const Command& c : kCommands)
        std::fprintf(out, "  %-12s %s\n", c.name, c.summary);
    std::fprintf(out, "\n'spatter-bench COMMAND --help' describes a command.\n");
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
        std::strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return 0;
    }
    for (const Command& c : kCommands)
        if (std::strcmp(argv[1], c.name) == 0) return c.run(argc - 1, argv + 1);
    std::fprintf(stderr, "spatter-bench: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
