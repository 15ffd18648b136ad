#include "spatter/render/Renderer.hpp"

#include "DecalBatch.hpp"
#include "DecalRecordBuffers.hpp"
#include "DecalRouting.hpp"
#include "GBuffer.hpp"
#include "GlObjects.hpp"
#include "GlState.hpp"
#include "GpuLayouts.hpp"
#include "GpuTimers.hpp"
#include "NormalMatrix.hpp"
#include "OverlayMeshes.hpp"
#include "RendererShaders.hpp"
#include "SceneGpu.hpp"
#include "ShaderProgram.hpp"
#include "TextureSpaceDecals.hpp"
#include "VolumetricDecals.hpp"

#include "spatter/core/UvOverlap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>

namespace spatter {

using namespace render_detail;

namespace {

bool finiteVec(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Status validateSettings(const RendererSettings& s) {
    if (s.width <= 0 || s.height <= 0 || s.width > 16384 || s.height > 16384)
        return fail("renderer: size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                    " is out of range");
    if (!std::isfinite(s.wrapMaxAngleDeg) || s.wrapMaxAngleDeg < 0.0f || s.wrapMaxAngleDeg > 180.0f)
        return fail("renderer: wrapMaxAngleDeg must be in [0, 180]");
    if (!std::isfinite(s.fadeStart) || s.fadeStart < 0.0f || s.fadeStart >= 1.0f)
        return fail("renderer: fadeStart must be in [0, 1)");
    const LightSettings& l = s.light;
    if (!finiteVec(l.direction) || !(glm::length(l.direction) > 0.0f) || !finiteVec(l.color) ||
        !std::isfinite(l.intensity) || !finiteVec(l.skyAmbient) || !finiteVec(l.groundAmbient) ||
        !std::isfinite(l.exposure))
        return fail("renderer: light settings must be finite with a non-zero direction");
    return {};
}

// Distance from p to the box (0 inside) and to its farthest corner.
void distanceRange(const DBounds& b, const glm::dvec3& p, double& nearest, double& farthest) {
    const glm::dvec3 closest = glm::clamp(p, b.min, b.max);
    nearest = glm::length(closest - p);
    const glm::dvec3 far = glm::max(glm::abs(b.min - p), glm::abs(b.max - p));
    farthest = glm::length(far);
}

bool finiteDirection(const glm::vec3& v) {
    return finiteVec(v) && glm::length(v) > 1e-12f;
}

// Bounds of the position deltas of every morph target of `o`.
std::vector<Bounds> morphBounds(const SceneObject& o) {
    std::vector<Bounds> out(o.morphTargets.size());
    for (size_t t = 0; t < out.size(); ++t)
        for (const glm::vec3& d : o.morphTargets[t].positions)
            out[t].extend(d);
    return out;
}

// `rest` grown by every delta the weighted targets can add (per axis, a bound of the sum).
Bounds morphedBounds(const Bounds& rest, const std::vector<Bounds>& deltas, const std::vector<double>& w) {
    if (rest.empty()) return rest;
    Bounds b = rest;
    for (size_t t = 0; t < deltas.size() && t < w.size(); ++t) {
        if (deltas[t].empty()) continue;
        const glm::vec3 a = deltas[t].min * float(w[t]), c = deltas[t].max * float(w[t]);
        b.min += glm::min(a, c);
        b.max += glm::max(a, c);
    }
    return b;
}

// Extends `world` by the corners of `b` mapped by `m`.
void extendByBox(DBounds& world, const Bounds& b, const glm::dmat4& m) {
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                           (c & 4) ? b.max.z : b.min.z);
        world.extend(glm::dvec3(m * glm::dvec4(p, 1.0)));
    }
}

// Empty when `pose` fits a scene of these counts, else the first problem.
std::string poseProblem(const ScenePose& pose, const std::vector<size_t>& skinJoints,
                        const std::vector<size_t>& morphTargets) {
    const size_t n = morphTargets.size();
    if (pose.objectTransforms.size() != n)
        return std::to_string(pose.objectTransforms.size()) + " object transforms for " + std::to_string(n) +
               " objects";
    if (pose.morphWeights.size() != n)
        return std::to_string(pose.morphWeights.size()) + " morph weight lists for " + std::to_string(n) +
               " objects";
    if (pose.jointMatrices.size() != skinJoints.size())
        return std::to_string(pose.jointMatrices.size()) + " joint matrix lists for " +
               std::to_string(skinJoints.size()) + " skins";
    for (size_t i = 0; i < n; ++i) {
        const std::string object = "object " + std::to_string(i);
        if (const std::string p = transformProblem(pose.objectTransforms[i]); !p.empty())
            return object + ": " + p;
        const std::vector<double>& w = pose.morphWeights[i];
        if (w.size() != morphTargets[i])
            return object + ": " + std::to_string(w.size()) + " morph weights for " +
                   std::to_string(morphTargets[i]) + " morph targets";
        for (double v : w)
            if (!std::isfinite(v)) return object + ": morph weight is not finite";
    }
    for (size_t s = 0; s < skinJoints.size(); ++s) {
        const std::string skin = "skin " + std::to_string(s);
        if (pose.jointMatrices[s].size() != skinJoints[s])
            return skin + ": " + std::to_string(pose.jointMatrices[s].size()) + " joint matrices for " +
                   std::to_string(skinJoints[s]) + " joints";
        for (size_t j = 0; j < skinJoints[s]; ++j)
            if (const std::string p = transformProblem(pose.jointMatrices[s][j]); !p.empty())
                return skin + " joint " + std::to_string(j) + ": " + p;
    }
    return {};
}

} // namespace

struct Renderer::Impl {
    ContextInfo info;
    RendererSettings settings;

    GBuffer gbuffer;
    SceneGpu scene;
    std::vector<glm::dmat4> transforms;
    std::vector<uint8_t> objectIds;
    std::vector<uint8_t> receivers;  // 1: drawn before the decals
    std::vector<Bounds> localBounds; // object space, morphed by the current pose
    bool hasDynamic = false;
    bool hasLate = false;

    std::optional<DecalProjector> projector; // the decal pass, as any host uses it
    VolumetricDecals volumetric;
    std::vector<DecalType> types; // as given to setDecalTypes, for the craters

    // Texture-space decals and deformation, per object.
    std::vector<Mesh> meshes; // render meshes, for the UV check of setObjectDecalMode
    std::vector<std::string> names;
    std::vector<Deformation> deformations;
    double time = 0.0;
    TextureSpaceDecals textureSpace;
    DecalBatch splatBatch;
    DecalRouting routing; // which decals the renderer draws itself: craters and splats
    DecalRecordBuffers splatRecords;
    GlBuffer splatTypes, splatLists;

    // Tells the projector which decals are the renderer's.
    void updateHostDrawn() { projector->setHostDrawn(routing.hostTypes(), routing.hostObjects()); }

    GlProgram geometryProgram, lightingProgram, viewProgram;
    GlProgram meshOverlayProgram, boxOverlayProgram; // built on first use
    OverlayMeshes overlayMeshes;

    GlBuffer frameBuffer;
    GlBuffer objectBuffer;
    size_t objectCapacity = 0;
    GlVertexArray emptyVao;
    GlTexture zeroIds; // bound as s_ids when there is no ID target

    // Skinning and morphing (setPose): counts of the scene, then the pose, in double.
    size_t nodeCount = 0;
    std::vector<int> objectSkins;                // SceneObject::skin, -1 where not skinned
    std::vector<size_t> skinJoints, morphCounts; // joints per skin, morph targets per object
    std::vector<Bounds> restBounds;
    std::vector<std::vector<Bounds>> deltaBounds; // per object, per morph target
    bool posed = false;
    std::vector<std::vector<glm::dmat4>> jointMatrices;
    GlBuffer jointBuffer, weightBuffer;
    std::vector<glm::mat4> jointScratch;

    GpuTimers timers;
    uint64_t frame = 0;
    bool rendered = false;
    Camera lastCamera;               // of the last render
    glm::dvec2 depthProjection{0.0}; // A, B of the last frame's projection: view z = -B / (depth + A)

    // Per-frame counters.
    size_t drawCalls = 0;
    size_t triangles = 0;

    // The overlay program with vertex stage `vert`, built into `slot` on first use.
    static Result<GLuint> overlayProgram(GlProgram& slot, const char* vert) {
        if (slot) return slot.get();
        Result<GlProgram> p =
            buildProgram(shaderLibrary(kRendererShaders),
                         {{GL_VERTEX_SHADER, vert}, {GL_FRAGMENT_SHADER, "overlay.frag"}}, {});
        if (!p) return fail("renderer: " + p.error());
        slot = std::move(p.value());
        return slot.get();
    }

    void bindBuffers() const {
        glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlock, frameBuffer.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kObjectBuffer, objectBuffer.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBuffer, scene.materialBuffer());
        const ProjectorResources decals = projector->resources();
        bindDecalRecords(decals.decalBounds, decals.decals);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBuffer, decals.visible);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecalTypeBuffer, decals.types);
    }

    GLuint idTexture() const { return gbuffer.hasIds() ? gbuffer.ids() : zeroIds.get(); }
    // The draw buffer of the face normal target, where the G-buffer has one.
    GLenum faceBuffer() const { return gbuffer.hasFaceNormals() ? GL_COLOR_ATTACHMENT5 : GL_NONE; }

    // State every pass starts from.
    void baseState(GLuint framebuffer) const {
        resetPassState(framebuffer, gbuffer.width(), gbuffer.height(), false);
        bindBuffers();
    }

    bool skinned(size_t object) const { return posed && objectSkins[object] >= 0; }

    void bindPoseBuffers() const {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPoseObjectBuffer, scene.poseObjectBuffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInfluenceBuffer, scene.influenceBuffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMorphDeltaBuffer, scene.morphDeltaBuffer());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kJointBuffer, jointBuffer.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMorphWeightBuffer, weightBuffer.get());
    }

    // Camera-relative joint matrices of the pose, composed in double, sent as float.
    void uploadJoints(const glm::dvec3& eye) {
        if (!posed || scene.jointCount() == 0) return;
        const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -eye);
        jointScratch.resize(scene.jointCount());
        for (size_t s = 0; s < jointMatrices.size(); ++s)
            for (size_t j = 0; j < jointMatrices[s].size(); ++j)
                jointScratch[scene.firstJoint(s) + j] = glm::mat4(toEye * jointMatrices[s][j]);
        glNamedBufferSubData(jointBuffer.get(), 0, GLsizeiptr(jointScratch.size() * sizeof(glm::mat4)),
                             jointScratch.data());
    }

    // World bounds of object i at the current pose.
    void extendWorld(DBounds& world, size_t i) const {
        const Bounds& b = localBounds[i];
        if (b.empty()) return;
        if (!skinned(i)) return extendByBox(world, b, transforms[i]);
        // A skinned vertex is a convex combination of its joints' images: inside the joints' boxes.
        for (const glm::dmat4& j : jointMatrices[size_t(objectSkins[i])])
            extendByBox(world, b, j);
    }

    // Takes the scene's skinning and morphing counts; the scene starts unposed.
    void resetPose(const Scene& s) {
        const size_t n = s.objects.size();
        nodeCount = s.animation.nodes.size();
        objectSkins.resize(n);
        morphCounts.resize(n);
        restBounds.resize(n);
        deltaBounds.resize(n);
        for (size_t i = 0; i < n; ++i) {
            objectSkins[i] = s.objects[i].skinWeights.influences > 0 ? s.objects[i].skin : -1;
            morphCounts[i] = s.objects[i].morphTargets.size();
            restBounds[i] = s.objects[i].mesh->bounds();
            deltaBounds[i] = morphBounds(s.objects[i]);
        }
        skinJoints.clear();
        for (const Skin& skin : s.animation.skins)
            skinJoints.push_back(skin.joints.size());
        posed = false;
        jointMatrices.clear();
        jointBuffer = createBuffer();
        glNamedBufferStorage(jointBuffer.get(), GLsizeiptr(std::max<size_t>(1, scene.jointCount()) * 64),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
        weightBuffer = createBuffer();
        glNamedBufferStorage(weightBuffer.get(), GLsizeiptr(std::max<size_t>(1, scene.weightCount()) * 4),
                             nullptr, GL_DYNAMIC_STORAGE_BIT);
    }

    // Takes a pose that passed poseProblem.
    void applyPose(const ScenePose& pose) {
        transforms = pose.objectTransforms;
        jointMatrices = pose.jointMatrices;
        std::vector<float> weights(std::max<size_t>(1, scene.weightCount()), 0.0f);
        for (size_t i = 0; i < morphCounts.size(); ++i) {
            for (size_t t = 0; t < morphCounts[i]; ++t)
                weights[scene.firstWeight(i) + t] = float(pose.morphWeights[i][t]);
            localBounds[i] = morphedBounds(restBounds[i], deltaBounds[i], pose.morphWeights[i]);
        }
        glNamedBufferSubData(weightBuffer.get(), 0, GLsizeiptr(weights.size() * sizeof(float)),
                             weights.data());
        posed = true;
    }

    void drawObjects(bool receiversPass) {
        glUseProgram(geometryProgram.get());
        bindPoseBuffers();
        glUniform1ui(2, posed ? 1u : 0u);
        glUniform1ui(3, gbuffer.hasFaceNormals() ? 1u : 0u);
        for (size_t i = 0; i < scene.objectCount(); ++i) {
            if ((receivers[i] != 0) != receiversPass) continue;
            const GpuMesh& mesh = scene.mesh(i);
            if (mesh.triangles == 0) continue;
            glBindVertexArray(mesh.vao.get());
            glUniform1ui(0, GLuint(i));
            glBindTextureUnit(2, textureSpace.albedo(i));
            glBindTextureUnit(3, textureSpace.normal(i));
            for (const GpuSubmesh& sm : mesh.submeshes) {
                if (sm.indexCount == 0) continue;
                glUniform1ui(1, sm.material);
                glBindTextureUnit(0, scene.baseColorTexture(sm.material));
                glBindTextureUnit(1, scene.normalTexture(sm.material));
                glDrawElements(GL_TRIANGLES, GLsizei(sm.indexCount), GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(uintptr_t(sm.firstIndex) * sizeof(uint32_t)));
                ++drawCalls;
                triangles += sm.indexCount / 3;
            }
        }
    }

    // Pass 1: clears the G-buffer and draws the decal receivers (for the coverage view, with their
    // texture-space decals' coverage).
    void geometryPass(bool coverage) {
        baseState(gbuffer.framebuffer());
        const GLenum all[6] = {
            GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
            GL_COLOR_ATTACHMENT2, GLenum(gbuffer.hasIds() ? GL_COLOR_ATTACHMENT3 : GL_NONE),
            GL_COLOR_ATTACHMENT4, faceBuffer()};
        glDrawBuffers(6, all);
        const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLuint zeroU[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, zero);
        glClearBufferfv(GL_COLOR, 2, zero);
        if (gbuffer.hasIds()) glClearBufferuiv(GL_COLOR, 3, zeroU);
        glClearBufferfv(GL_COLOR, 4, zero);
        if (gbuffer.hasFaceNormals()) glClearBufferfv(GL_COLOR, 5, zero);
        glDepthMask(GL_TRUE);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 0.0f, 0); // reversed-Z: 0 is infinitely far

        const GLenum geometry[6] = {GL_COLOR_ATTACHMENT0,
                                    GL_COLOR_ATTACHMENT1,
                                    GL_COLOR_ATTACHMENT2,
                                    GLenum(gbuffer.hasIds() ? GL_COLOR_ATTACHMENT3 : GL_NONE),
                                    GLenum(coverage ? GL_COLOR_ATTACHMENT4 : GL_NONE),
                                    faceBuffer()};
        glDrawBuffers(6, geometry);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glEnable(GL_FRAMEBUFFER_SRGB);
        drawObjects(true);
    }

    // After the projector added a decal texture layer: the splats' instances see it too.
    Result<int> layerAdded(Result<int> layer) {
        if (layer) splatBatch.configure(settings.wrapMaxAngleDeg, projector->decalTextureCutouts());
        return layer;
    }

    // The G-buffer as the projector's host frame (pass 2: the decals, or their coverage).
    HostFrame hostFrame(const Camera& camera) const {
        HostFrame f;
        f.width = gbuffer.width();
        f.height = gbuffer.height();
        f.view = viewRotation(camera) * glm::translate(glm::dmat4(1.0), -camera.eye);
        f.projection = projection(camera, double(f.width) / double(f.height));
        f.eye = camera.eye;
        f.depth = {gbuffer.depth(), DepthEncoding::Window, ClipDepth::ZeroToOne, true};
        f.normals = {gbuffer.normal(), NormalEncoding::OctahedralWorld};
        f.albedoTexture = gbuffer.albedo();
        f.roughness = {gbuffer.material(), 0};
        f.objectIdTexture = gbuffer.hasIds() ? gbuffer.ids() : 0;
        f.faceNormalTexture = gbuffer.faceNormals();
        return f;
    }

    // Pass 3: objects that take no decals, over whatever the decals wrote.
    void latePass(bool coverage) {
        baseState(gbuffer.framebuffer());
        const GLenum buffers[6] = {GL_COLOR_ATTACHMENT0,
                                   GL_COLOR_ATTACHMENT1,
                                   GL_COLOR_ATTACHMENT2,
                                   GLenum(gbuffer.hasIds() ? GL_COLOR_ATTACHMENT3 : GL_NONE),
                                   GLenum(coverage ? GL_COLOR_ATTACHMENT4 : GL_NONE),
                                   faceBuffer()};
        glDrawBuffers(6, buffers);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glEnable(GL_FRAMEBUFFER_SRGB);
        drawObjects(false);
    }

    // Pass 4: lighting, or a debug view, into the output image.
    void outputPass(View view) {
        baseState(gbuffer.outputFramebuffer());
        glBindTextureUnit(0, gbuffer.depth());
        glBindTextureUnit(1, gbuffer.albedo());
        glBindTextureUnit(2, gbuffer.normal());
        glBindTextureUnit(3, gbuffer.material());
        glBindTextureUnit(4, idTexture());
        glBindTextureUnit(5, gbuffer.coverage());
        glBindVertexArray(emptyVao.get());
        if (view == View::Final) {
            glUseProgram(lightingProgram.get());
        } else {
            glUseProgram(viewProgram.get());
            glUniform1i(0, int(view)); // View values 1..5 match u_viewMode
        }
        glDrawArrays(GL_TRIANGLES, 0, 3);
        ++drawCalls;
    }

    // Pass 5: line overlays over the output image, depth-tested against the scene unless always
    // on top. `meshProgram` draws the wireframes and `boxProgram` `boxes` decal boxes (the first
    // entries of the visible list); either may be 0 to skip it. Returns the lines drawn.
    size_t overlayPass(const RenderOverlays& o, GLuint meshProgram, GLuint boxProgram, size_t boxes) {
        baseState(gbuffer.overlayFramebuffer());
        if (!o.alwaysOnTop) {
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_GEQUAL); // reversed-Z: not behind the scene
        }
        const float depthScale = o.alwaysOnTop ? 1.0f : 1.0f - o.depthBias;
        size_t lines = 0;
        if (meshProgram != 0) {
            glUseProgram(meshProgram);
            glUniform1f(0, depthScale);
            glBindVertexArray(overlayMeshes.vertexArray());
            glDrawElements(GL_LINES, GLsizei(overlayMeshes.indexCount()), GL_UNSIGNED_INT, nullptr);
            ++drawCalls;
            lines += overlayMeshes.lineCount();
        }
        if (boxProgram != 0) {
            glUseProgram(boxProgram);
            glUniform1f(0, depthScale);
            glBindVertexArray(emptyVao.get());
            glDrawArraysInstanced(GL_LINES, 0, 24, GLsizei(boxes));
            ++drawCalls;
            lines += 12 * boxes;
        }
        glDisable(GL_DEPTH_TEST);
        return lines;
    }

    void uploadFrame(const Camera& camera) {
        const double aspect = double(gbuffer.width()) / double(gbuffer.height());
        const glm::dmat4 proj = projection(camera, aspect);
        const glm::dmat4 view = viewRotation(camera);
        FrameGpu f{};
        f.viewProj = glm::mat4(proj * view);
        f.view = glm::mat4(view);
        f.invView = glm::mat4(glm::transpose(view));
        f.projection = glm::vec4(float(proj[0][0]), float(proj[1][1]), float(proj[2][2]), float(proj[3][2]));
        depthProjection = glm::dvec2(proj[2][2], proj[3][2]);
        f.viewport = glm::vec4(float(gbuffer.width()), float(gbuffer.height()), 1.0f / float(gbuffer.width()),
                               1.0f / float(gbuffer.height()));
        const LightSettings& l = settings.light;
        f.lightDirection = glm::vec4(glm::normalize(l.direction), l.intensity);
        f.lightColor = glm::vec4(l.color, l.exposure);
        f.skyAmbient = glm::vec4(l.skyAmbient, 0.0f);
        f.groundAmbient = glm::vec4(l.groundAmbient, 0.0f);

        DBounds world;
        for (size_t i = 0; i < transforms.size(); ++i)
            extendWorld(world, i);
        double nearest = 0.0, farthest = 1.0;
        if (!world.empty()) distanceRange(world, camera.eye, nearest, farthest);
        f.depthRange =
            glm::vec4(float(nearest), float(std::max(farthest, nearest + 1e-6)), settings.fadeStart, 0.0f);
        glNamedBufferSubData(frameBuffer.get(), 0, sizeof(FrameGpu), &f);

        std::vector<ObjectGpu> objects(transforms.size());
        const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -camera.eye);
        for (size_t i = 0; i < transforms.size(); ++i) {
            const glm::dmat4 rel = toEye * transforms[i];
            ObjectGpu& o = objects[i];
            o.model = glm::mat4(rel);
            o.normalMatrix = glm::mat4(glm::mat3(normalMatrix(glm::dmat3(transforms[i]))));
            // A skinned object mirrors as its first joint does (skins rarely mix handedness).
            const glm::dmat4& handed = skinned(i) && !jointMatrices[size_t(objectSkins[i])].empty()
                                           ? jointMatrices[size_t(objectSkins[i])][0]
                                           : transforms[i];
            o.info = glm::uvec4(gbuffer.hasIds() ? objectIds[i] : 0u,
                                glm::determinant(glm::dmat3(handed)) < 0.0 ? 1u : 0u,
                                textureSpace.enabled(i) ? 1u : 0u, 0u);
            const Deformation& d = deformations[i];
            if (d.amplitude != 0.0f) {
                o.deformA = glm::vec4(glm::normalize(d.displacement) * d.amplitude, d.frequency);
                const double phase = double(d.phase) + double(d.speed) * time;
                o.deformB = glm::vec4(glm::normalize(d.waveDirection),
                                      float(std::fmod(phase, 2.0 * 3.14159265358979323846)));
            }
        }
        if (!objects.empty())
            glNamedBufferSubData(objectBuffer.get(), 0, GLsizeiptr(objects.size() * sizeof(ObjectGpu)),
                                 objects.data());
        uploadJoints(camera.eye);
    }

    // Splats the pending decals of texture-space objects into their textures, one instanced draw per
    // object, then dilates each; returns the decals splatted. Meshes are splatted in the pose of this
    // frame (after uploadFrame): the pose the decal system placed the decals against.
    Result<size_t> splatPending(const glm::dvec3& eye, size_t& invalid) {
        std::vector<Decal>& pendingSplats = routing.pendingSplats();
        if (pendingSplats.empty()) return size_t(0);
        splatBatch.setObjectCount(transforms.size());
        splatBatch.setDecals(pendingSplats);
        pendingSplats.clear();
        std::vector<std::vector<uint32_t>> perObject(transforms.size());
        const std::vector<DecalRecordGpu>& inst = splatBatch.instances();
        invalid = 0;
        for (size_t i = 0; i < inst.size(); ++i) {
            if (splatBatch.valid(i))
                perObject[inst[i].info.x].push_back(uint32_t(i));
            else
                ++invalid;
        }
        std::vector<uint32_t> lists;
        for (const auto& l : perObject)
            lists.insert(lists.end(), l.begin(), l.end());
        if (lists.empty()) return size_t(0);
        splatRecords.assign(inst);
        const std::vector<DecalTypeGpu>& typeRecords = splatBatch.typeRecords();
        splatTypes = createBuffer();
        glNamedBufferStorage(splatTypes.get(), GLsizeiptr(typeRecords.size() * sizeof(DecalTypeGpu)),
                             typeRecords.data(), 0);
        splatLists = createBuffer();
        glNamedBufferStorage(splatLists.get(), GLsizeiptr(lists.size() * sizeof(uint32_t)), lists.data(), 0);
        splatBatch.markUploaded();
        TextureSpaceDecals::SplatInputs in{splatRecords.bounds(),
                                           splatRecords.bodies(),
                                           splatTypes.get(),
                                           splatLists.get(),
                                           projector->resources().albedoLayers,
                                           projector->resources().normalLayers,
                                           posed,
                                           {}};
        const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -eye);
        for (size_t o = 0; o < perObject.size(); ++o)
            in.worldToObject.push_back(perObject[o].empty() ? glm::mat4(1.0f)
                                                            : glm::mat4(glm::inverse(toEye * transforms[o])));
        bindPoseBuffers();
        Result<size_t> n = textureSpace.splat(perObject, scene, in, settings.fadeStart, drawCalls);
        splatBatch.setDecals({});
        return n;
    }
};

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<Renderer> Renderer::create(const GlContext& context, const RendererSettings& settings) {
    if (Status s = validateSettings(settings); !s) return fail(s.error());
    if (Status s = context.makeCurrent(); !s) return fail("renderer: " + s.error());
    auto impl = std::make_unique<Impl>();
    impl->info = context.info();
    impl->settings = settings;

    Result<GlProgram> geometry =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "geometry.vert"}, {GL_FRAGMENT_SHADER, "geometry.frag"}}, {});
    if (!geometry) return fail("renderer: " + geometry.error());
    Result<GlProgram> lighting =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "lighting.frag"}}, {});
    if (!lighting) return fail("renderer: " + lighting.error());
    Result<GlProgram> view =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "view.frag"}}, {});
    if (!view) return fail("renderer: " + view.error());
    impl->geometryProgram = std::move(geometry.value());
    impl->lightingProgram = std::move(lighting.value());
    impl->viewProgram = std::move(view.value());

    if (Status s = impl->gbuffer.create(settings.width, settings.height, false, settings.faceNormals); !s)
        return fail("renderer: " + s.error());
    ProjectorSettings projector;
    projector.wrapMaxAngleDeg = settings.wrapMaxAngleDeg;
    projector.fadeStart = settings.fadeStart;
    projector.normalFrame = settings.normalFrame;
    projector.decalTextureSize = settings.decalTextureSize;
    projector.waitForTimers = settings.waitForTimers;
    projector.gpuCullingFrom = settings.gpuCullingFrom;
    projector.gpuCullingInViewFrom = settings.gpuCullingInViewFrom;
    projector.occlusionCulling = settings.occlusionCulling;
    projector.stageTimers = settings.decalStageTimers;
    projector.deferredResolve = settings.deferredResolve;
    projector.restoreGlState = false; // every pass of the renderer starts from resetPassState
    Result<DecalProjector> p = DecalProjector::create(projector);
    if (!p) return fail("renderer: " + p.error());
    impl->projector.emplace(std::move(p).value());
    impl->splatBatch.configure(settings.wrapMaxAngleDeg, impl->projector->decalTextureCutouts());

    impl->frameBuffer = createBuffer();
    glNamedBufferStorage(impl->frameBuffer.get(), sizeof(FrameGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    // Placeholders so that every binding point has a buffer before the first scene.
    impl->objectBuffer = createBuffer();
    glNamedBufferStorage(impl->objectBuffer.get(), sizeof(ObjectGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    impl->emptyVao = createVertexArray();
    impl->zeroIds = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(impl->zeroIds.get(), 1, GL_R8UI, 1, 1);
    const uint8_t zero = 0;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(impl->zeroIds.get(), 0, 0, 0, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    glTextureParameteri(impl->zeroIds.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(impl->zeroIds.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (Status s = impl->volumetric.create(); !s) return fail("renderer: " + s.error());
    impl->timers.create();

    Renderer r(std::move(impl));
    if (Status s = r.setScene(Scene{}); !s) return fail(s.error());
    return r;
}

Status Renderer::setScene(const Scene& scene) {
    Impl& m = *impl_;
    if (Status s = m.scene.upload(scene); !s) return s;
    const size_t n = scene.objects.size();
    m.transforms.resize(n);
    m.receivers.resize(n);
    m.localBounds.resize(n);
    m.hasDynamic = false;
    m.hasLate = false;
    m.meshes.resize(n);
    m.names.resize(n);
    m.deformations.assign(n, Deformation{});
    std::vector<uint8_t> deforming(n);
    for (size_t i = 0; i < n; ++i)
        deforming[i] = scene.objects[i].deforms() ? 1 : 0;
    m.routing.reset(deforming);
    m.textureSpace.reset(n);
    for (size_t i = 0; i < n; ++i) {
        const SceneObject& o = scene.objects[i];
        m.meshes[i] = *o.mesh;
        m.names[i] = o.name;
        m.transforms[i] = o.transform;
        m.receivers[i] = o.receivesDecals ? 1 : 0;
        m.localBounds[i] = o.mesh->bounds();
        m.hasDynamic = m.hasDynamic || o.dynamic;
        m.hasLate = m.hasLate || !o.receivesDecals;
    }
    m.objectIds.assign(n, 0);
    m.resetPose(scene);
    if (m.hasDynamic != m.gbuffer.hasIds())
        if (Status s = m.gbuffer.create(m.gbuffer.width(), m.gbuffer.height(), m.hasDynamic,
                                        m.gbuffer.hasFaceNormals());
            !s)
            return fail("renderer: " + s.error());
    if (n > m.objectCapacity || m.objectCapacity == 0) {
        m.objectCapacity = std::max<size_t>(n, 1);
        m.objectBuffer = createBuffer();
        glNamedBufferStorage(m.objectBuffer.get(), GLsizeiptr(m.objectCapacity * sizeof(ObjectGpu)), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
    }
    m.updateHostDrawn();
    m.projector->setDecals({});
    m.routing.take({}, {}, m.types, m.volumetric);
    m.overlayMeshes.clear();
    return {};
}

Status Renderer::setObjectTransform(uint32_t object, const glm::dmat4& transform) {
    Impl& m = *impl_;
    if (object >= m.transforms.size())
        return fail("renderer: object " + std::to_string(object) + " is out of range (" +
                    std::to_string(m.transforms.size()) + " objects)");
    if (const std::string problem = transformProblem(transform); !problem.empty())
        return fail("renderer: object " + std::to_string(object) + ": " + problem);
    m.transforms[object] = transform;
    return {};
}

Status Renderer::setPose(const ScenePose& pose) {
    Impl& m = *impl_;
    if (const std::string p = poseProblem(pose, m.skinJoints, m.morphCounts); !p.empty())
        return fail("renderer: pose: " + p);
    m.applyPose(pose);
    return {};
}

Status Renderer::setPose(const SceneEvaluator& evaluator) {
    Impl& m = *impl_;
    if (evaluator.nodeWorld().size() != m.nodeCount)
        return fail("renderer: pose: the evaluator has " + std::to_string(evaluator.nodeWorld().size()) +
                    " nodes, the scene " + std::to_string(m.nodeCount));
    ScenePose pose;
    for (size_t i = 0; i < m.transforms.size(); ++i) {
        pose.objectTransforms.push_back(evaluator.objectTransform(i));
        pose.morphWeights.push_back(evaluator.morphWeights(i));
    }
    for (size_t s = 0; s < m.skinJoints.size(); ++s)
        pose.jointMatrices.push_back(evaluator.jointMatrices(s));
    return setPose(pose);
}

Status Renderer::setObjectIds(const std::vector<uint8_t>& ids) {
    Impl& m = *impl_;
    if (ids.size() != m.transforms.size())
        return fail("renderer: " + std::to_string(ids.size()) + " object IDs for " +
                    std::to_string(m.transforms.size()) + " objects");
    m.objectIds = ids;
    return {};
}

Status Renderer::setObjectDecalMode(uint32_t object, DecalMode mode, int textureSize) {
    Impl& m = *impl_;
    if (object >= m.transforms.size())
        return fail("renderer: object " + std::to_string(object) + " is out of range (" +
                    std::to_string(m.transforms.size()) + " objects)");
    const std::string name = "renderer: object " + std::to_string(object) + " (" + m.names[object] + ")";
    if (mode == DecalMode::Projected) {
        m.textureSpace.disable(object);
        m.routing.setMode(object, mode);
        m.updateHostDrawn();
        return {};
    }
    if (textureSize < 16 || textureSize > 4096 || (textureSize & (textureSize - 1)) != 0)
        return fail(name + ": decal texture size " + std::to_string(textureSize) +
                    " is not a power of two in [16, 4096]");
    Result<UvOverlapReport> uv = findUvOverlaps(m.meshes[object]);
    if (!uv) return fail(name + " cannot take texture-space decals: " + uv.error());
    if (!uv->usable()) return fail(name + " cannot take texture-space decals: its UVs have " + uv->summary());
    if (Status s = m.textureSpace.enable(object, textureSize, m.scene.mesh(object)); !s)
        return fail("renderer: " + s.error());
    m.routing.setMode(object, mode);
    m.updateHostDrawn();
    return {};
}

DecalMode Renderer::objectDecalMode(uint32_t object) const {
    return impl_->routing.mode(object);
}

Status Renderer::clearObjectDecals(uint32_t object) {
    Impl& m = *impl_;
    if (object >= m.transforms.size() || !m.textureSpace.enabled(object))
        return fail("renderer: object " + std::to_string(object) + " has no texture-space decals to clear");
    m.textureSpace.clear(object);
    return {};
}

Status Renderer::setObjectDeformation(uint32_t object, const Deformation& d) {
    Impl& m = *impl_;
    if (object >= m.transforms.size())
        return fail("renderer: object " + std::to_string(object) + " is out of range (" +
                    std::to_string(m.transforms.size()) + " objects)");
    if (!std::isfinite(d.amplitude) || !std::isfinite(d.frequency) || !std::isfinite(d.phase) ||
        !std::isfinite(d.speed) || !finiteDirection(d.displacement) || !finiteDirection(d.waveDirection))
        return fail("renderer: deformation of object " + std::to_string(object) +
                    " must be finite with non-zero directions");
    m.deformations[object] = d;
    return {};
}

Status Renderer::setTime(double seconds) {
    if (!std::isfinite(seconds)) return fail("renderer: time must be finite");
    impl_->time = seconds;
    return {};
}

void Renderer::setDecalTypes(const std::vector<DecalType>& types) {
    impl_->types = types;
    impl_->projector->setDecalTypes(types);
    impl_->splatBatch.setTypes(types);
    impl_->routing.setTypes(types);
    impl_->updateHostDrawn();
}

void Renderer::setDecals(const std::vector<Decal>& decals, const CraterClipsOf& clips) {
    Impl& m = *impl_;
    m.projector->setDecals(decals);
    m.routing.take(decals, clips, m.types, m.volumetric);
}

void Renderer::updateDecals(const std::vector<Decal>& decals, const DecalChanges& changes,
                            const CraterClipsOf& clips) {
    Impl& m = *impl_;
    m.projector->updateDecals(decals, changes);
    if (!m.routing.replay(decals, clips, changes, m.types, m.volumetric))
        m.routing.take(decals, clips, m.types, m.volumetric);
}

Result<int> Renderer::addDecalTexture(const Image& albedo, const Image& normalMap) {
    return impl_->layerAdded(impl_->projector->addDecalTexture(albedo, normalMap));
}

Result<int> Renderer::addDecalTextureFile(const std::string& albedoPath, const std::string& normalMapPath) {
    return impl_->layerAdded(impl_->projector->addDecalTextureFile(albedoPath, normalMapPath));
}

ProjectorMemory Renderer::decalMemory() const {
    return impl_->projector->memory();
}

int Renderer::decalTextureLayers() const {
    return impl_->projector->decalTextureLayers();
}

Status Renderer::setOverlayMeshes(const std::vector<Mesh>& meshes) {
    return impl_->overlayMeshes.set(meshes, impl_->transforms.size());
}

Status Renderer::resize(int width, int height) {
    RendererSettings s = impl_->settings;
    s.width = width;
    s.height = height;
    if (Status v = validateSettings(s); !v) return v;
    if (Status c = impl_->gbuffer.create(width, height, impl_->hasDynamic, impl_->gbuffer.hasFaceNormals());
        !c)
        return fail("renderer: " + c.error());
    impl_->settings = s;
    return {};
}

Status Renderer::setLight(const LightSettings& light) {
    RendererSettings s = impl_->settings;
    s.light = light;
    if (Status v = validateSettings(s); !v) return v;
    impl_->settings = s;
    return {};
}

const RendererSettings& Renderer::settings() const {
    return impl_->settings;
}

Result<FrameStats> Renderer::render(const Camera& camera, View view) {
    RenderOptions options;
    options.view = view;
    return render(camera, options);
}

Result<FrameStats> Renderer::render(const Camera& camera, const RenderOptions& options) {
    Impl& m = *impl_;
    if (Status s = validateCamera(camera); !s) return fail("renderer: " + s.error());
    const RenderOverlays& overlays = options.overlays;
    if (!std::isfinite(overlays.depthBias) || overlays.depthBias < 0.0f || overlays.depthBias > 0.5f)
        return fail("renderer: overlay depth bias " + std::to_string(overlays.depthBias) +
                    " is outside [0, 0.5]");
    const View view = options.view;
    const auto start = std::chrono::steady_clock::now();
    const bool coverage = view == View::Coverage;
    m.drawCalls = 0;
    m.triangles = 0;

    FrameStats stats;
    stats.frame = m.frame;
    stats.width = m.gbuffer.width();
    stats.height = m.gbuffer.height();
    stats.view = view;
    stats.glRenderer = m.info.renderer;
    stats.glVendor = m.info.vendor;
    stats.glVersion = m.info.version;

    GLuint meshOverlay = 0, boxOverlay = 0;
    if (overlays.proxyWireframe && m.overlayMeshes.indexCount() > 0) {
        Result<GLuint> p = Impl::overlayProgram(m.meshOverlayProgram, "overlay_mesh.vert");
        if (!p) return fail(p.error());
        meshOverlay = p.value();
    }
    if (overlays.decalBoxes) {
        Result<GLuint> p = Impl::overlayProgram(m.boxOverlayProgram, "overlay_box.vert");
        if (!p) return fail(p.error());
        boxOverlay = p.value();
    }

    m.timers.beginFrame(m.frame);
    m.uploadFrame(camera);
    if (!m.routing.pendingSplats().empty()) {
        m.timers.begin(GpuPass::Splat);
        size_t invalid = 0;
        Result<size_t> splatted = m.splatPending(camera.eye, invalid);
        m.timers.end();
        if (!splatted) {
            m.timers.endFrame(false);
            return fail(splatted.error());
        }
        stats.decalsSplatted = splatted.value();
        stats.decalsInvalid += invalid;
    }
    stats.decalsTextureSpace = m.routing.textureSpaceCount();
    stats.textureSpaceObjects = m.textureSpace.objectCount();
    stats.textureSpaceBytes = m.textureSpace.bytes();

    m.timers.begin(GpuPass::Geometry);
    m.geometryPass(coverage);
    m.timers.end();
    stats.decalsVolumetric = m.volumetric.size();
    stats.decalsInvalid += m.volumetric.invalidCount();
    if (m.volumetric.size() > 0) {
        m.timers.begin(GpuPass::Volumetric);
        m.baseState(m.gbuffer.framebuffer());
        const bool compareIds = m.gbuffer.hasIds() && options.decals.idClipping;
        m.drawCalls +=
            m.volumetric.draw(m.gbuffer, m.idTexture(), compareIds, coverage, m.transforms, camera.eye);
        m.timers.end();
    }
    // Pass 2, by the projector (it times itself: GL timer queries do not nest).
    ProjectorDraw draw;
    draw.coverageTexture = coverage ? m.gbuffer.coverage() : 0;
    draw.idClipping = options.decals.idClipping;
    draw.angleReject = options.decals.angleReject;
    if (Status s = m.projector->setObjects(m.transforms, m.objectIds); !s) {
        m.timers.endFrame(false);
        return fail("renderer: " + s.error());
    }
    Result<ProjectorStats> decals = m.projector->draw(m.hostFrame(camera), draw);
    if (!decals) {
        m.timers.endFrame(false);
        return fail("renderer: " + decals.error());
    }
    stats.decals = decals->decals - m.volumetric.size() - m.routing.textureSpaceCount(); // those projected
    stats.decalsInvalid += decals->invalid;
    stats.decalsCulled = decals->culled;
    stats.decalsDrawn = decals->drawn;
    stats.decalsInside = decals->inside;
    stats.decalBytesUploaded = decals->bytesUploaded;
    stats.decalPassSkipped = decals->skipped;
    stats.decalVariant = decals->variant;
    stats.decalNormalCopy = decals->normalCopy;
    stats.decalStages = decals->stages;
    m.drawCalls += decals->drawCalls;
    if (m.hasLate) {
        m.timers.begin(GpuPass::Late);
        m.latePass(coverage);
        m.timers.end();
    }
    m.timers.begin(GpuPass::Lighting);
    m.outputPass(view);
    m.timers.end();
    if (stats.decalsDrawn == 0) boxOverlay = 0;
    if (meshOverlay != 0 || boxOverlay != 0) {
        m.timers.begin(GpuPass::Overlay);
        stats.overlayLines = m.overlayPass(overlays, meshOverlay, boxOverlay, stats.decalsDrawn);
        m.timers.end();
    }
    stats.gpu = m.timers.endFrame(m.settings.waitForTimers);
    stats.gpu.decalsMs = decals->gpuMs;

    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    stats.drawCalls = m.drawCalls;
    stats.triangles = m.triangles;
    stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++m.frame;
    m.rendered = true;
    m.lastCamera = camera;
    return stats;
}

Result<Image> Renderer::readback() const {
    const Impl& m = *impl_;
    if (!m.rendered) return fail("renderer: nothing rendered yet");
    const int w = m.gbuffer.width(), h = m.gbuffer.height();
    std::vector<uint8_t> pixels(size_t(w) * size_t(h) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(m.gbuffer.output(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()),
                      pixels.data());
    Image image;
    image.width = w;
    image.height = h;
    image.name = "render";
    image.rgba.resize(pixels.size());
    const size_t row = size_t(w) * 4;
    for (int y = 0; y < h; ++y) // GL row 0 is the bottom
        std::copy_n(&pixels[size_t(h - 1 - y) * row], row, &image.rgba[size_t(y) * row]);
    return image;
}

Result<uint64_t> Renderer::findSurface(const std::vector<SurfaceLine>& lines) {
    Impl& m = *impl_;
    if (!m.rendered) return fail("renderer: nothing rendered yet");
    m.timers.untimedWork();
    return m.projector->findSurface(m.hostFrame(m.lastCamera), lines);
}

std::optional<std::vector<SurfacePoint>> Renderer::surfaceFound(uint64_t request, bool wait) {
    return impl_->projector->surfaceFound(request, wait);
}

Result<std::vector<float>> Renderer::readbackDepth() const {
    const Impl& m = *impl_;
    if (!m.rendered) return fail("renderer: nothing rendered yet");
    const int w = m.gbuffer.width(), h = m.gbuffer.height();
    std::vector<float> depth(size_t(w) * size_t(h));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(m.gbuffer.depth(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      GLsizei(depth.size() * sizeof(float)), depth.data());
    std::vector<float> distance(depth.size(), 0.0f);
    const glm::dvec2 p = m.depthProjection;
    for (int y = 0; y < h; ++y) // GL row 0 is the bottom
        for (int x = 0; x < w; ++x) {
            const double d = depth[size_t(h - 1 - y) * size_t(w) + size_t(x)];
            if (d > 0.0) distance[size_t(y) * size_t(w) + size_t(x)] = float(p.y / (d + p.x));
        }
    return distance;
}

void Renderer::present(int framebufferWidth, int framebufferHeight) const {
    const Impl& m = *impl_;
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(m.gbuffer.outputFramebuffer(), 0, 0, 0, m.gbuffer.width(), m.gbuffer.height(), 0,
                           0, framebufferWidth, framebufferHeight, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

} // namespace spatter
