#include "Memory.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"
#include "InstanceMemory.hpp"
#include "RawEmbree.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProcessMemory.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/DecalTextures.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kMemoryCommand = "memory";

// Objects of the mesh in the rows of a mesh placed many times.
constexpr size_t kPlacedCopies = 100;

const char* kMemoryUsage =
    R"(usage: spatter-bench memory [MESH] [--decals N] [--no-gpu] [--quick] [--json FILE]

Bytes per decal and per object, measured:

  decal system   C heap (glibc mallinfo2, or ASan's statistics in an ASan build) taken by N
                 decals spawned with spawnAttached, spread so that a cell of the area grid holds
                 about 8: the decal records, the per-decal bookkeeping, the area grid and the
                 handle slots (the containers' growth included); and the same by the system's own
                 count, by what it serves (DecalSystem::memory)
  renderer CPU   what the projector holds on the CPU for the decals by its own count
                 (DecalProjector::memory: the draw order, validity bits, and the decal records while it
                 culls on the CPU), and the C heap the renderer keeps after Renderer::setDecals and 35
                 frames (with what the GL driver allocates: some drivers keep copies of the buffers
                 that the GPU row counts)
  renderer GPU   record bytes uploaded in the first frame (FrameStats); the projector's buffers
                 (DecalProjector::memory), those sized by the decals held apart from those sized by
                 the viewport; and the GPU memory the driver reports gone after 35 frames
                 (GL_NVX_gpu_memory_info) where the driver has it, else the resident set growth (a
                 software renderer keeps its buffers in process memory). The frames after the first
                 count: the GPU's counts of the decals in view arrive a frame late and pick the
                 occlusion test and the screen tiles, whose buffers come then, and a copy of the
                 normals that the draws stopped reading is freed after 30 draws
  per object     a proxy of MESH (meshoptimizer, 0.5%): its mesh; the Embree BVH of it as the
                 collision world builds it (user geometry) and as Embree's own triangles (device
                 memory monitor); the collision world; one decal texture array layer; a
                 texture-space decal texture (FrameStats::textureSpaceBytes)
  placed 100     MESH placed 100 times, static, with its proxy: the scene's and the proxy list's C
  times          heap with the objects sharing the one mesh and proxy (kept once), against each given
                 a copy, and the collision world built from them

Target: at most 160 bytes per decal for 1,000,000 decals, decal system, renderer CPU and GPU together.

MESH        as in `tradeoff` (default stanford-bunny.obj when the shared data is there, else
            builtin:gallery)
--decals N  decals (default 1000000)        --no-gpu  no OpenGL context (renderer rows skipped)
--quick     20,000 decals, a 64 x 128 UV sphere unless MESH is given (smoke test)
--json FILE {"cpu_bytes_per_decal", "gpu_bytes_per_decal", "renderer_cpu_bytes_per_decal",
            "total_mb_per_million", "objects": {...}, ...}
)";

long nvxAvailableKb() {
    if (!epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) return -1;
    glFinish();
    GLint kb = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &kb);
    return long(kb);
}

template <class T> size_t bytesOf(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

size_t meshBytes(const Mesh& m) {
    return bytesOf(m.positions) + bytesOf(m.normals) + bytesOf(m.uvs) + bytesOf(m.tangents) +
           bytesOf(m.indices) + bytesOf(m.submeshes);
}

// Frames rendered after the first before the renderer's memory is read: enough for the GPU's counts
// to pick the resolve and for a copy of the normals that draws no longer read to be freed
// (ProjectorMemory::kNormalCopyIdleDraws).
constexpr int kSettleFrames = ProjectorMemory::kNormalCopyIdleDraws + 4;
static_assert(kSettleFrames + 1 == 35, "the help text and the report say 35 frames");

double mb(double bytes) {
    return bytes / 1e6;
}

} // namespace

int runMemoryCommand(int argc, char** argv) {
    Result<Args> parsed =
        parseArgs(argc, argv, {"--decals", "--json"}, {"--no-gpu", "--quick", "--help", "-h"});
    if (!parsed) return usageError(kMemoryCommand, parsed.error());
    const Args& args = parsed.value();
    if (args.has("--help") || args.has("-h")) {
        std::cout << kMemoryUsage;
        return 0;
    }
    if (args.positional.size() > 1) return usageError(kMemoryCommand, "at most one MESH");
    const bool quick = args.has("--quick");
    Result<uint64_t> decalCount = parseCount(args.value("--decals", quick ? "20000" : "1000000"), "--decals");
    if (!decalCount) return usageError(kMemoryCommand, decalCount.error());
    const size_t n = decalCount.value();
    if (n == 0 || n > (1u << 30)) return usageError(kMemoryCommand, "--decals must be in [1, 2^30]");

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench memory: %zu decals\nmachine: %s\n", n, describe(machine).c_str());
    Json j;
    j["command"] = "memory";
    j["machine"] = toJson(machine);
    j["decals"] = n;

    // ---- The decal system ----
    const DecalFieldView view = decalFieldView(16.0 / 9.0);
    const Scene field = decalFieldScene(view, false);
    DecalSettings ds;
    ds.budget = uint32_t(n);
    ds.maxPerObject = uint32_t(n);
    // Spread over a square where a 0.5-unit cell holds about 8 decals (maxPerCell is 16).
    const double side = std::sqrt(double(n) / 8.0) * double(ds.cellSize);
    Result<CollisionWorld> world = CollisionWorld::build(field);
    if (!world) {
        std::cerr << "spatter-bench memory: " << world.error() << "\n";
        return 1;
    }
    Result<DecalSystem> sys = DecalSystem::create(std::move(world).value(), ds);
    if (!sys) {
        std::cerr << "spatter-bench memory: " << sys.error() << "\n";
        return 1;
    }
    DecalType type;
    type.name = "memory";
    const uint16_t ti = sys->registerType(type).value();
    Rng rng(1);
    std::vector<glm::vec3> positions(n);
    for (glm::vec3& p : positions)
        p = glm::vec3(float(side) * rng.uniform(-0.5f, 0.5f), 0.0f, float(side) * rng.uniform(-0.5f, 0.5f));
    const size_t heap0 = heapBytes(), rss0 = residentBytes();
    for (const glm::vec3& p : positions)
        sys->spawnAttached(0, p, glm::vec3(0.0f, 1.0f, 0.0f), ti);
    const size_t heap1 = heapBytes(), rss1 = residentBytes();
    const size_t placed = sys->decals().size();
    const double cpuPerDecal = double(heap1 - heap0) / double(placed);
    std::printf("\ndecal system: %zu decals placed, %zu evicted; heap %+.1f MB (%.1f B per decal), resident "
                "%+.1f MB\n",
                placed, size_t(sys->stats().evicted), mb(double(heap1 - heap0)), cpuPerDecal,
                mb(double(rss1) - double(rss0)));
    std::printf(
        "  of which the Decal record itself: %zu B (sizeof); a game that keeps a DecalHandle per decal adds "
        "%zu B\n",
        sizeof(Decal), sizeof(DecalHandle));
    const DecalSystemMemory own = sys->memory();
    const auto perDecal = [&](size_t bytes) { return double(bytes) / double(placed); };
    std::printf("  by its own count %.1f B per decal: records %.1f, handles %.1f, area limits %.1f, change "
                "list %.1f, other %.1f\n",
                perDecal(own.total()), perDecal(own.records), perDecal(own.handles), perDecal(own.areaLimits),
                perDecal(own.changeLog), perDecal(own.other));
    Json ownJson;
    ownJson["records"] = own.records;
    ownJson["handles"] = own.handles;
    ownJson["area_limits"] = own.areaLimits;
    ownJson["change_log"] = own.changeLog;
    ownJson["other"] = own.other;
    j["decal_system_bytes"] = ownJson;
    j["cpu_bytes_per_decal"] = cpuPerDecal;
    j["cpu_resident_bytes_per_decal"] = (double(rss1) - double(rss0)) / double(placed);
    j["decal_record_bytes"] = sizeof(Decal);
    j["handle_bytes"] = sizeof(DecalHandle);
    j["placed"] = placed;
    j["area_side"] = side;

    // ---- The renderer ----
    double rendererCpu = std::nan(""), rendererCpuHeap = std::nan(""), gpuPerDecal = std::nan(""),
           gpuMeasured = std::nan(""), gpuHeld = std::nan("");
    std::string gpuHow = "not measured";
    Json objects;
    if (!args.has("--no-gpu")) {
        Result<GlContext> gl = GlContext::createHeadless();
        if (!gl) {
            std::printf("renderer: no OpenGL context (%s)\n", gl.error().c_str());
            j["gl_renderer"] = nullptr;
        } else {
            j["gl_renderer"] = gl->info().renderer;
            std::printf("renderer: %s\n", gl->info().renderer.c_str());
            RendererSettings rs;
            rs.width = 1920;
            rs.height = 1080;
            const long vram0 = nvxAvailableKb();
            const size_t rssCreate0 = residentBytes();
            Result<Renderer> renderer = Renderer::create(gl.value(), rs);
            if (!renderer) {
                std::cerr << "spatter-bench memory: " << renderer.error() << "\n";
                return 1;
            }
            const long vram1 = nvxAvailableKb();
            const size_t rssCreate1 = residentBytes();
            if (Status s = renderer->setScene(field); !s) {
                std::cerr << "spatter-bench memory: " << s.error() << "\n";
                return 1;
            }
            renderer->setDecalTypes({type});
            renderer->render(view.camera, View::Final); // everything but the decals allocated
            const long vram2 = nvxAvailableKb();
            const size_t h0 = heapBytes(), r0 = residentBytes();
            renderer->setDecals(sys->decals());
            const size_t r1 = residentBytes();
            Result<FrameStats> frame = renderer->render(view.camera, View::Final);
            if (!frame) {
                std::cerr << "spatter-bench memory: " << frame.error() << "\n";
                return 1;
            }
            // The frames after the first settle what the renderer keeps: the GPU's counts of the
            // decals in view arrive a frame late and pick the occlusion test and the screen tiles, and
            // the copy of the normals goes once the compute resolve has drawn for a while.
            for (int settle = 0; settle < kSettleFrames; ++settle)
                if (!renderer->render(view.camera, View::Final)) return 1;
            const long vram3 = nvxAvailableKb();
            const size_t h1 = heapBytes(), r2 = residentBytes(); // what stays after the upload
            const ProjectorMemory held = renderer->decalMemory();
            rendererCpuHeap = (double(h1) - double(h0)) / double(placed);
            rendererCpu = double(held.cpuBytes) / double(placed);
            gpuHeld = double(held.gpuBufferBytes) / double(placed);
            const double uploaded = double(frame->decalBytesUploaded);
            const double visibleBytes = 4.0 * double(frame->decalsDrawn), typeBytes = 48.0;
            gpuPerDecal = (uploaded - visibleBytes - typeBytes) / double(placed);
            if (vram2 >= 0 && vram3 >= 0) {
                gpuMeasured = double(vram2 - vram3) * 1024.0 / double(placed);
                gpuHow = "GL_NVX_gpu_memory_info";
            } else {
                gpuMeasured = (double(r2) - double(r1)) / double(placed);
                gpuHow = "resident set growth over the frames (software renderer)";
            }
            std::printf(
                "renderer CPU: the projector's own count %.1f B per decal; the heap after setDecals and 35 "
                "frames %+.1f MB (%.1f B per decal, the GL driver's allocations included), resident %+.1f "
                "MB\n",
                rendererCpu, mb(double(h1) - double(h0)), rendererCpuHeap, mb(double(r1) - double(r0)));
            const double screen = double(held.gpuScreenBytes);
            std::printf(
                "renderer GPU: the projector's buffers %.1f B per decal (capacities): %.1f B per decal "
                "sized by the decals held, %.1f MB by the viewport and the decals in view\n",
                gpuHeld, (double(held.gpuBufferBytes) - screen) / double(placed), mb(screen));
            std::printf("renderer GPU: first frame uploaded %.1f MB: %.1f B per decal of records + 4 B per "
                        "visible decal (%zu visible) + one type\n",
                        mb(uploaded), gpuPerDecal, frame->decalsDrawn);
            std::printf("              memory gone: %.1f B per decal (%s)\n", gpuMeasured, gpuHow.c_str());
            if (vram2 >= 0 && vram3 >= 0) {
                const double driver = double(vram2 - vram3) * 1024.0 - double(held.gpuBufferBytes);
                std::printf(
                    "              of which beyond the projector's buffers (the driver's own): %.1f MB\n",
                    mb(driver));
                j["gpu_driver_bytes"] = driver;
            }
            j["renderer_cpu_bytes_per_decal"] = rendererCpu;
            j["renderer_cpu_heap_bytes_per_decal"] = rendererCpuHeap;
            j["gpu_buffer_bytes_per_decal"] = gpuHeld;
            j["gpu_screen_buffer_bytes"] = screen;
            j["renderer_cpu_resident_bytes_per_decal"] = (double(r1) - double(r0)) / double(placed);
            j["gpu_bytes_per_decal"] = gpuPerDecal;
            j["gpu_bytes_per_visible_decal"] = 4;
            j["gpu_measured_bytes_per_decal"] = number(gpuMeasured);
            j["gpu_measured_how"] = gpuHow;
            j["visible"] = frame->decalsDrawn;
            if (vram0 >= 0 && vram1 >= 0) j["renderer_create_gpu_bytes"] = double(vram0 - vram1) * 1024.0;
            j["renderer_create_resident_bytes"] = double(rssCreate1) - double(rssCreate0);

            // One more decal texture layer.
            const DecalTextureImages images =
                makeBuiltinDecalTexture(DecalTexture::Blood, rs.decalTextureSize);
            const long t0 = nvxAvailableKb();
            const size_t tr0 = residentBytes();
            Result<int> layer = renderer->addDecalTexture(images.albedo, images.normal);
            renderer->render(view.camera, View::Final);
            const long t1 = nvxAvailableKb();
            const size_t tr1 = residentBytes();
            const int size = rs.decalTextureSize;
            const double layerBytes = 2.0 * 4.0 * double(size) * double(size) * 4.0 / 3.0;
            Json layerJson;
            layerJson["size"] = size;
            layerJson["computed_bytes"] = layerBytes;
            if (layer && t0 >= 0 && t1 >= 0) layerJson["measured_gpu_bytes"] = double(t0 - t1) * 1024.0;
            if (layer) layerJson["measured_resident_bytes"] = double(tr1) - double(tr0);
            objects["decal_texture_layer"] = layerJson;
            std::printf("decal texture layer (%dx%d, albedo + normal map, mipmaps): %.0f KB computed", size,
                        size, layerBytes / 1024.0);
            if (layer && t0 >= 0 && t1 >= 0) std::printf(", %.0f KB measured", double(t0 - t1));
            std::printf("\n");

            // A texture-space decal texture on a unit square with UVs in [0, 1].
            Scene square;
            square.source = "unit square";
            SceneObject so;
            so.name = "square";
            so.mesh = shareMesh(makeGrid({0.0f, 1.0f}, {0.0f, 1.0f}));
            square.objects.push_back(std::move(so));
            if (renderer->setScene(square)) {
                Json ts = Json::object();
                for (int texSize : {512, 1024}) {
                    if (!renderer->setObjectDecalMode(0, DecalMode::TextureSpace, texSize)) continue;
                    Camera c;
                    c.eye = glm::dvec3(0.5, 2.0, 0.5);
                    c.target = glm::dvec3(0.5, 0.0, 0.5);
                    c.up = glm::dvec3(0.0, 0.0, -1.0);
                    Result<FrameStats> f = renderer->render(c, View::Final);
                    if (f) ts[std::to_string(texSize)] = f->textureSpaceBytes;
                    if (f)
                        std::printf(
                            "texture-space decal texture %dx%d: %.0f KB (FrameStats::textureSpaceBytes)\n",
                            texSize, texSize, double(f->textureSpaceBytes) / 1024.0);
                }
                objects["texture_space_bytes"] = ts;
            }
        }
    }

    // ---- Per object: proxy, BVH, collision world ----
    std::optional<InputMesh> input;
    if (!args.positional.empty() || !quick) {
        std::string spec = args.positional.empty() ? std::string("stanford-bunny.obj") : args.positional[0];
        if (args.positional.empty() && resolveInput(spec).empty()) spec = "builtin:gallery";
        Result<InputMesh> loaded = loadInputMesh(spec, 0);
        if (!loaded) {
            std::cerr << "spatter-bench memory: " << loaded.error() << "\n";
            return 1;
        }
        input = std::move(loaded).value();
    } else {
        input.emplace();
        input->name = "sphere";
        input->mesh = makeSphere(1.0f, 64, 128);
    }
    ProxySettings ps;
    ps.backend = ProxyBackend::MeshOpt;
    ps.tolerance = 0.005f;
    Result<Proxy> proxy = buildProxy(input->mesh, ps);
    if (!proxy) {
        std::cerr << "spatter-bench memory: proxy of " << input->name << ": " << proxy.error() << "\n";
        return 1;
    }
    const size_t tris = proxy->mesh.triangleCount();
    const double proxyBytes = double(meshBytes(proxy->mesh));
    Result<RawEmbree> userBvh = RawEmbree::build(proxy->mesh, RawGeometry::User);
    Result<RawEmbree> triBvh = RawEmbree::build(proxy->mesh, RawGeometry::Triangles);
    const Scene proxyScene = singleObjectScene(input->mesh, input->name);
    const size_t wh0 = heapBytes(), wr0 = residentBytes();
    std::optional<CollisionWorld> proxyWorld;
    {
        Result<CollisionWorld> w = CollisionWorld::build(proxyScene, {shareProxy(proxy.value())});
        if (w) proxyWorld.emplace(std::move(w).value());
    }
    const size_t wh1 = heapBytes(), wr1 = residentBytes();
    std::printf("\nper object (%s, %zu render triangles; meshoptimizer proxy at 0.5%%: %zu triangles):\n",
                input->name.c_str(), input->mesh.triangleCount(), tris);
    std::printf("  proxy mesh            %8.1f KB  %6.1f B per triangle\n", proxyBytes / 1024.0,
                proxyBytes / double(tris));
    Json proxyJson;
    proxyJson["mesh"] = input->name;
    proxyJson["render_triangles"] = input->mesh.triangleCount();
    proxyJson["proxy_triangles"] = tris;
    proxyJson["proxy_bytes"] = proxyBytes;
    if (userBvh) {
        std::printf("  BVH, user geometry    %8.1f KB  %6.1f B per triangle (Embree memory monitor)\n",
                    double(userBvh->deviceBytes()) / 1024.0, double(userBvh->deviceBytes()) / double(tris));
        proxyJson["bvh_user_bytes"] = userBvh->deviceBytes();
    }
    if (triBvh) {
        std::printf("  BVH, Embree triangles %8.1f KB  %6.1f B per triangle (for comparison)\n",
                    double(triBvh->deviceBytes()) / 1024.0, double(triBvh->deviceBytes()) / double(tris));
        proxyJson["bvh_triangles_bytes"] = triBvh->deviceBytes();
    }
    if (proxyWorld) {
        std::printf(
            "  collision world       %8.1f KB heap, %.1f KB resident (positions, indices, the float copy "
            "Embree traces, BVH)\n",
            double(wh1 - wh0) / 1024.0, (double(wr1) - double(wr0)) / 1024.0);
        proxyJson["world_heap_bytes"] = double(wh1 - wh0);
        proxyJson["world_resident_bytes"] = double(wr1) - double(wr0);
    }
    objects["proxy"] = proxyJson;
    objects["placed"] = instanceMemory(input->mesh, proxy.value(), kPlacedCopies);
    j["objects"] = objects;

    // ---- Targets ----
    const double million = 1e6;
    const double totalPerDecal =
        cpuPerDecal + (std::isnan(rendererCpu) ? 0.0 : rendererCpu) +
        std::max({std::isnan(gpuMeasured) ? 0.0 : gpuMeasured, std::isnan(gpuPerDecal) ? 0.0 : gpuPerDecal,
                  std::isnan(gpuHeld) ? 0.0 : gpuHeld});
    const double rendererCpuPart = std::isnan(rendererCpu) ? 0.0 : rendererCpu;
    // The target is for a million decals with the renderer's parts measured.
    const bool judged =
        n == 1000000 && !std::isnan(rendererCpu) && totalPerDecal > cpuPerDecal + rendererCpuPart;
    const bool met = totalPerDecal <= 160.0;
    std::printf(
        "\nper decal: decal system %.1f B + renderer CPU %.1f B + GPU %.1f B = %.1f B, target <= 160: "
        "%s\n",
        cpuPerDecal, rendererCpuPart, totalPerDecal - cpuPerDecal - rendererCpuPart, totalPerDecal,
        !judged ? "not judged (it is for 1,000,000 decals with the renderer measured)"
        : met   ? "met"
                : "missed");
    std::printf("1,000,000 decals: %.0f MB\n", mb(totalPerDecal * million));
    j["total_bytes_per_decal"] = totalPerDecal;
    j["total_mb_per_million"] = mb(totalPerDecal * million);
    Json targets;
    targets["total_met"] = judged ? Json(met) : Json();
    j["targets"] = targets;
    if (args.has("--json"))
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench memory: " << s.error() << "\n";
            return 1;
        }
    return 0;
}

} // namespace spatter::bench
