#include "Interactive.hpp"

#include "GallerySim.hpp"
#include "GalleryView.hpp"
#include "SurfaceLaying.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <iostream>

namespace spatter::gallery {

namespace {

// First-person camera: position, yaw about +Y and pitch, in radians.
struct Player {
    glm::dvec3 eye{0.0, 1.7, 7.5};
    double yaw = 0.0; // 0 looks down -Z
    double pitch = -0.05;

    glm::dvec3 forward() const {
        return {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
    }
    Camera camera(double nearPlane) const {
        Camera c;
        c.eye = eye;
        c.target = eye + forward();
        c.nearPlane = nearPlane;
        return c;
    }
};

struct Trigger {
    double interval = 0.1; // seconds between automatic shots while held
    double cooldown = 0.0;
    // True when a shot fires this frame: on the press, then every interval while held.
    bool fire(bool held, double dt) {
        cooldown -= dt;
        if (!held) {
            cooldown = 0.0;
            return false;
        }
        if (cooldown > 0.0) return false;
        cooldown = interval;
        return true;
    }
};

struct Hud {
    RenderOptions options;
    bool wrapAround = true;
    bool volumetricBullets = true;
    bool layOnDrawnSurface = true; // new flat decals laid on the drawn surface a frame after their shot
    uint64_t laid = 0, removed = 0, spawned = 0; // decals laid, removed (shot too steep), placed for
                                                 // shots the proxy refused, so far
    uint64_t replaced = 0;                       // decals whose shot met the drawn surface before their box
    float tolerance = 0.5f;
    double lastPlacementUs = 0.0;
    std::string lastResult;
    std::string status;
    // A rebuild of the proxies on a thread of its own while the gallery plays on (declared in this
    // order so that the future, which waits for the thread, goes before the progress it writes).
    std::atomic<float> rebuildProgress{0.0f};
    std::future<Result<ProxySet>> rebuild;
};

// Starts building the proxies at the HUD's tolerance on a thread of its own, unless a build runs.
void startRebuild(Hud& hud, const GallerySim& sim) {
    if (hud.rebuild.valid()) return;
    hud.rebuildProgress = 0.0f;
    const float tolerance = hud.tolerance;
    hud.rebuild = std::async(std::launch::async, [&sim, &hud, tolerance] {
        return sim.buildProxies(tolerance, &hud.rebuildProgress);
    });
}

// Takes the rebuilt proxies once their thread is done: a fresh decal system, the renderer prepared
// for it, and what the HUD and the console say.
void finishRebuild(Hud& hud, GallerySim& sim, Renderer& renderer) {
    if (!hud.rebuild.valid() || hud.rebuild.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    Result<ProxySet> set = hud.rebuild.get();
    Status s = set ? sim.useProxies(std::move(set).value()) : Status(fail(set.error()));
    if (s) s = prepareRenderer(renderer, sim);
    hud.status = s ? "proxies rebuilt in " + std::to_string(sim.proxySeconds()) + " s" : s.error();
    std::cout << "spatter-gallery: " << hud.status << std::endl;
}

const View kViews[] = {View::Final, View::Albedo, View::Normal, View::Depth, View::Ids, View::Coverage};

void drawHud(Hud& hud, GallerySim& sim, Renderer& renderer, const FrameStats& frame) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("spatter gallery", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    const DecalStats& st = sim.decals().stats();
    ImGui::Text("decals alive %zu   placed %llu   evicted %llu", st.alive, (unsigned long long)st.placed,
                (unsigned long long)st.evicted);
    ImGui::Text("shots %llu   on moving targets %llu (skinned %llu)",
                (unsigned long long)sim.counters().shots, (unsigned long long)sim.counters().onMovingTargets,
                (unsigned long long)sim.counters().onSkinnedTargets);
    const double avgUs =
        sim.counters().shots ? 1e6 * sim.counters().placementSeconds / double(sim.counters().shots) : 0.0;
    ImGui::Text("placement: last %.1f us, mean %.1f us per shot", hud.lastPlacementUs, avgUs);
    ImGui::Text("last shot: %s", hud.lastResult.c_str());
    ImGui::Text("GPU: decal pass %.3f ms, frame %.3f ms", frame.gpu.decalsMs, frame.gpu.totalMs());
    ImGui::Text("decals drawn %zu, culled %zu, camera inside %zu, volumetric %zu (%.3f ms)",
                frame.decalsDrawn, frame.decalsCulled, frame.decalsInside, frame.decalsVolumetric,
                frame.gpu.volumetricMs);
    ImGui::Text("triangles: render %zu, proxy %zu", sim.renderTriangles(), sim.proxyTriangles());
    ImGui::Text("proxy error bound h = %.4f m", sim.errorBound());
    ImGui::Separator();
    int viewIndex = 0;
    for (int i = 0; i < 6; ++i)
        if (kViews[i] == hud.options.view) viewIndex = i;
    if (ImGui::Combo("view", &viewIndex, "final\0albedo\0normal\0depth\0ids\0coverage\0"))
        hud.options.view = kViews[viewIndex];
    ImGui::Checkbox("proxy wireframe", &hud.options.overlays.proxyWireframe);
    ImGui::SameLine();
    ImGui::Checkbox("decal boxes", &hud.options.overlays.decalBoxes);
    ImGui::Checkbox("ID clipping", &hud.options.decals.idClipping);
    ImGui::SameLine();
    ImGui::Checkbox("angle reject", &hud.options.decals.angleReject);
    if (ImGui::Checkbox("paint wraps around corners", &hud.wrapAround)) {
        sim.setPaintWrapAround(hud.wrapAround);
        renderer.setDecalTypes(sim.types());
    }
    ImGui::Checkbox("volumetric bullet holes", &hud.volumetricBullets);
    ImGui::Checkbox("lay new decals on the drawn surface", &hud.layOnDrawnSurface);
    ImGui::SameLine();
    ImGui::Text("(%llu laid, %llu replaced, %llu removed, %llu refused shots placed)",
                (unsigned long long)hud.laid, (unsigned long long)hud.replaced,
                (unsigned long long)hud.removed, (unsigned long long)hud.spawned);
    ImGui::SliderFloat("proxy tolerance %", &hud.tolerance, 0.0f, 5.0f, "%.2f");
    if (hud.rebuild.valid()) {
        ImGui::ProgressBar(hud.rebuildProgress.load(), ImVec2(-1.0f, 0.0f), "building proxies");
    } else if (ImGui::Button("rebuild proxies (clears decals)")) {
        startRebuild(hud, sim);
    }
    if (!hud.status.empty()) ImGui::TextWrapped("%s", hud.status.c_str());
    ImGui::Separator();
    ImGui::TextUnformatted("LMB bullet  RMB paint  F scorch  WASD/QE move  F5/F9 save/load  R rebuild "
                           "proxies  Tab cursor  Esc quit");
    ImGui::End();

    // Crosshair.
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImVec2 c(ImGui::GetIO().DisplaySize.x * 0.5f, ImGui::GetIO().DisplaySize.y * 0.5f);
    draw->AddLine(ImVec2(c.x - 8, c.y), ImVec2(c.x + 8, c.y), IM_COL32(255, 255, 255, 220), 1.5f);
    draw->AddLine(ImVec2(c.x, c.y - 8), ImVec2(c.x, c.y + 8), IM_COL32(255, 255, 255, 220), 1.5f);
}

// F5: the decals to `path`; what the HUD and the console say.
std::string quickSave(const GallerySim& sim, const std::string& path) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    const Status s = sim.save(path);
    return s ? "saved " + std::to_string(sim.decals().decals().size()) + " decals to " + path : s.error();
}

// F9: the decals from `path`; what the HUD and the console say.
std::string quickLoad(GallerySim& sim, const std::string& path) {
    const Result<DecalLoadReport> r = sim.load(path);
    if (!r) return r.error();
    return "loaded " + std::to_string(r->decals) + " decals (" + std::to_string(r->droppedDecals) +
           " dropped)";
}

} // namespace

int runInteractive(const GalleryOptions& options, GlContext& context) {
    Result<GallerySim> sim = GallerySim::create(options);
    if (!sim) {
        std::cerr << "spatter-gallery: " << sim.error() << "\n";
        return 1;
    }
    if (!options.loadPath.empty())
        if (Result<DecalLoadReport> r = sim->load(options.loadPath); !r) {
            std::cerr << "spatter-gallery: " << r.error() << "\n";
            return 1;
        }
    int fbw = 0, fbh = 0;
    context.framebufferSize(fbw, fbh);
    RendererSettings settings;
    settings.width = std::max(fbw, 16);
    settings.height = std::max(fbh, 16);
    settings.faceNormals = true; // the normals of the surface the shots' decals are laid on
    Result<Renderer> renderer = Renderer::create(context, settings);
    if (!renderer) {
        std::cerr << "spatter-gallery: " << renderer.error() << "\n";
        return 1;
    }
    if (Status s = prepareRenderer(renderer.value(), sim.value()); !s) {
        std::cerr << "spatter-gallery: " << s.error() << "\n";
        return 1;
    }

    GLFWwindow* window = context.window();
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    const Camera start = startCamera(sim->scene());
    Player player;
    player.eye = start.eye;
    const glm::dvec3 look = glm::normalize(start.target - start.eye);
    player.yaw = std::atan2(-look.x, -look.z);
    player.pitch = std::asin(std::clamp(look.y, -1.0, 1.0));
    const double moveSpeed = std::max(1.0, 0.15 * glm::length(sim->scene().worldBounds().extent()));

    bool captured = true;
    glfwSetInputMode(window, GLFW_CURSOR, GLFW_CURSOR_DISABLED);
    // A key pressed and released between two polls (or while the proxies were built) still counts.
    glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
    double mx = 0.0, my = 0.0;
    glfwGetCursorPos(window, &mx, &my);
    bool tabWasDown = false, scorchWasDown = false, saveWasDown = false, loadWasDown = false,
         rebuildWasDown = false;
    const std::string quickFile =
        options.savePath.empty() ? options.outDir + "/quick.save" : options.savePath;
    Trigger bullet{0.1}, paint{0.25};
    SurfaceLaying laying; // the shots' decals laid on the drawn surface a frame after they land
    Hud hud;
    hud.tolerance = options.tolerancePercent;
    FrameStats frame;
    int frames = 0;
    auto last = std::chrono::steady_clock::now();

    while (!context.shouldClose()) {
        context.pollEvents();
        const auto now = std::chrono::steady_clock::now();
        const double dt = std::min(0.1, std::chrono::duration<double>(now - last).count());
        last = now;

        if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(window, GLFW_TRUE);
        const bool tabDown = glfwGetKey(window, GLFW_KEY_TAB) == GLFW_PRESS;
        if (tabDown && !tabWasDown) {
            captured = !captured;
            glfwSetInputMode(window, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
        }
        tabWasDown = tabDown;

        double cx = 0.0, cy = 0.0;
        glfwGetCursorPos(window, &cx, &cy);
        if (captured) {
            player.yaw -= (cx - mx) * 0.0025;
            player.pitch = std::clamp(player.pitch - (cy - my) * 0.0025, -1.5, 1.5);
        }
        mx = cx;
        my = cy;

        const glm::dvec3 fwd = player.forward();
        const glm::dvec3 flat = glm::normalize(glm::dvec3(fwd.x, 0.0, fwd.z));
        const glm::dvec3 right(-flat.z, 0.0, flat.x);
        glm::dvec3 move(0.0);
        if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move += flat;
        if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move -= flat;
        if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move += right;
        if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move -= right;
        if (glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS) move.y += 1.0;
        if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) move.y -= 1.0;
        const double speed = moveSpeed * (glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 3.0 : 1.0);
        if (glm::length(move) > 0.0) player.eye += glm::normalize(move) * speed * dt;

        sim->advance(dt);
        const Camera camera = player.camera(start.nearPlane);
        context.framebufferSize(fbw, fbh);
        const double aspect = fbh > 0 ? double(fbw) / fbh : 1.0;

        const bool shooting = captured && !ImGui::GetIO().WantCaptureMouse;
        auto fire = [&](ShotKind kind) {
            const auto t0 = std::chrono::steady_clock::now();
            const GallerySim::Shot shot = sim->shoot(rayThrough(camera, aspect, 0.0, 0.0), kind);
            const SpawnResult& r = shot.result;
            if (hud.layOnDrawnSurface) laying.shot(shot, sim.value());
            hud.lastPlacementUs =
                1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            hud.lastResult = r.placed() ? "placed" : toString(r.status);
        };
        if (bullet.fire(shooting && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS, dt))
            fire(hud.volumetricBullets ? ShotKind::Crater : ShotKind::Bullet);
        if (paint.fire(shooting && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS, dt))
            fire(ShotKind::Paint);
        const bool scorchDown = glfwGetKey(window, GLFW_KEY_F) == GLFW_PRESS;
        if (scorchDown && !scorchWasDown && captured) fire(ShotKind::Scorch);
        scorchWasDown = scorchDown;
        const bool saveDown = glfwGetKey(window, GLFW_KEY_F5) == GLFW_PRESS;
        if (saveDown && !saveWasDown)
            std::cout << "spatter-gallery: " << (hud.status = quickSave(sim.value(), quickFile)) << std::endl;
        saveWasDown = saveDown;
        const bool loadDown = glfwGetKey(window, GLFW_KEY_F9) == GLFW_PRESS;
        if (loadDown && !loadWasDown)
            std::cout << "spatter-gallery: " << (hud.status = quickLoad(sim.value(), quickFile)) << std::endl;
        loadWasDown = loadDown;
        const bool rebuildDown = glfwGetKey(window, GLFW_KEY_R) == GLFW_PRESS;
        if (rebuildDown && !rebuildWasDown) startRebuild(hud, sim.value());
        rebuildWasDown = rebuildDown;

        if (fbw > 0 && fbh > 0) {
            if (fbw != renderer->settings().width || fbh != renderer->settings().height)
                renderer->resize(fbw, fbh);
            syncRenderer(renderer.value(), sim.value());
            if (Result<FrameStats> st = renderer->render(camera, hud.options); st) frame = st.value();
            laying.lay(renderer.value(), sim.value(), false);
            if (Status s = laying.search(renderer.value(), sim.value()); !s) hud.status = s.error();
            hud.laid = laying.laid();
            hud.removed = laying.removed();
            hud.replaced = laying.replaced();
            hud.spawned = laying.spawned();
            renderer->present(fbw, fbh);
        }

        finishRebuild(hud, sim.value(), renderer.value());
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        drawHud(hud, sim.value(), renderer.value(), frame);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        context.swapBuffers();

        if (++frames == 1) std::cout << "spatter-gallery: first frame shown" << std::endl;
        if (options.quitAfterFrames > 0 && frames >= options.quitAfterFrames)
            glfwSetWindowShouldClose(window, GLFW_TRUE);
    }

    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    std::cout << "spatter-gallery: " << sim->decals().stats().placed << " decals placed in " << frames
              << " frames\n";
    return 0;
}

} // namespace spatter::gallery
