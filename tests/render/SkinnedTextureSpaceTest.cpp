// Texture-space decals on a skinned object: a decal placed against the drawn pose is splatted in that
// pose, so the splat covers what the projected decal covers there, and it then rides the skin: at
// another pose it covers what the decal system's anchored decal covers there, without a second splat.
// The skinned object is a sheet bent at an elbow, whose UVs can hold texture-space decals.

#include "RenderTestSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr int kSplatView = 160;

// builtin:skinned-arm with its round bar (whose lathe UVs wrap) replaced by a sheet of the same
// length in the XY plane, facing +Z, its UVs one chart over the unit square, skinned as the bar is.
Scene skinnedSheet() {
    Scene scene = makeSkinnedArm();
    std::vector<float> across, along;
    for (int i = 0; i <= 12; ++i)
        across.push_back(float(i) / 12.0f);
    for (int i = 0; i <= 40; ++i)
        along.push_back(float(i) / 40.0f);
    glm::mat4 toArm(1.0f); // grid (x, 0, z) to (0.3 x - 0.15, 1 - z, 0)
    toArm[0] = glm::vec4(0.3f, 0.0f, 0.0f, 0.0f);
    toArm[1] = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    toArm[2] = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);
    toArm[3] = glm::vec4(-0.15f, 1.0f, 0.0f, 1.0f);
    Mesh sheet;
    appendMesh(sheet, makeGrid(across, along), toArm);
    SceneObject& o = scene.objects[0];
    SceneObject made = makeSceneObject("sheet", sheet, o.transform, true);
    made.node = o.node;
    made.skin = o.skin;
    made.skinWeights.influences = 2;
    for (const glm::vec3& p : sheet.positions) {
        const double t = std::clamp((double(p.y) - 0.35) / 0.3, 0.0, 1.0), w = t * t * (3.0 - 2.0 * t);
        made.skinWeights.joints.insert(made.skinWeights.joints.end(), {0, 1});
        made.skinWeights.weights.insert(made.skinWeights.weights.end(), {1.0 - w, w});
    }
    o = std::move(made);
    return scene;
}

struct ArmRig {
    Scene scene = skinnedSheet();
    SceneEvaluator evaluator{scene};
    DecalType type;

    ArmRig() {
        type.name = "mark";
        type.size = glm::vec2(0.12f);
        type.randomRotation = false;
        type.normalMap = false;
    }

    Status pose(double t, DecalSystem& system, Renderer& a, Renderer& b) {
        evaluator.evaluate(0, t);
        auto moved = system.setPose(0, evaluator.objectTransform(0), evaluator.jointMatrices(0), {});
        if (!moved) return fail(moved.error());
        if (Status s = a.setPose(evaluator); !s) return s;
        return b.setPose(evaluator);
    }
};

} // namespace

TEST(SkinnedTextureSpace, SplatMadeInTheDrawnPoseRidesTheSkinToAnotherPose) {
    SPATTER_REQUIRE_GL(gl);
    ArmRig rig;
    Result<DecalSystem> system = DecalSystem::create(rig.scene);
    ASSERT_TRUE(system.ok()) << system.error();
    const uint16_t type = system->registerType(rig.type).value();
    Result<Renderer> projected = makeRenderer(kSplatView, kSplatView);
    Result<Renderer> splatted = makeRenderer(kSplatView, kSplatView);
    ASSERT_TRUE(projected.ok() && splatted.ok());
    // An opaque square, so that the splat's coverage (where its texture shows) is the decal's
    // footprint, as the projected decal's is.
    Image opaque;
    opaque.width = opaque.height = 16;
    opaque.rgba.assign(16 * 16 * 4, 255);
    for (Renderer* r : {&projected.value(), &splatted.value()}) {
        ASSERT_TRUE(r->setScene(rig.scene).ok());
        Result<int> layer = r->addDecalTexture(opaque);
        ASSERT_TRUE(layer.ok()) << layer.error();
        rig.type.texture = layer.value();
        r->setDecalTypes({rig.type});
        ASSERT_TRUE(r->setObjectIds({system->objectId(0)}).ok());
    }
    Status mode = splatted->setObjectDecalMode(0, DecalMode::TextureSpace, 512);
    ASSERT_TRUE(mode.ok()) << mode.error();

    // Bent at the elbow (a quarter of the cycle), shot at the forearm from the front.
    ASSERT_TRUE(rig.pose(0.5, system.value(), projected.value(), splatted.value()).ok());
    const glm::dvec3 forearm(rig.evaluator.jointMatrices(0)[1] * glm::dvec4(0.0, 0.75, 0.0, 1.0));
    Ray shot;
    shot.origin = forearm + glm::dvec3(0.0, 0.0, 2.0);
    shot.direction = glm::dvec3(0.0, 0.0, -1.0);
    const SpawnResult placed = system->spawn(shot, type);
    ASSERT_TRUE(placed.placed()) << placed.reason;
    const Camera camera = lookAt(forearm + glm::dvec3(0.0, 0.0, 0.8), forearm);

    projected->setDecals({*system->get(placed.handle)});
    splatted->setDecals({*system->get(placed.handle)});
    FrameStats first;
    const std::vector<uint8_t> projectedAtSpawn =
        whiteMask(renderView(projected.value(), camera, View::Coverage));
    const std::vector<uint8_t> splatAtSpawn =
        whiteMask(renderView(splatted.value(), camera, View::Coverage, &first));
    EXPECT_EQ(first.decalsSplatted, 1u);
    EXPECT_GT(countSet(projectedAtSpawn), 150u);
    EXPECT_GT(iou(projectedAtSpawn, splatAtSpawn), 0.9) << "the splat was not made in the drawn pose";

    // Straighter again: the decal system moves the anchored decal with the skin; the splat is not
    // made again, and lies where the moved decal does.
    ASSERT_TRUE(rig.pose(0.2, system.value(), projected.value(), splatted.value()).ok());
    const Decal moved = *system->get(placed.handle);
    projected->setDecals({moved});
    splatted->setDecals({moved});
    FrameStats later;
    const std::vector<uint8_t> projectedLater =
        whiteMask(renderView(projected.value(), camera, View::Coverage));
    const std::vector<uint8_t> splatLater =
        whiteMask(renderView(splatted.value(), camera, View::Coverage, &later));
    EXPECT_EQ(later.decalsSplatted, 0u) << "the decal moved by the pose was splatted again";
    EXPECT_EQ(later.decalsTextureSpace, 1u);
    EXPECT_GT(countSet(projectedLater), 150u);
    EXPECT_LT(iou(projectedAtSpawn, projectedLater), 0.8) << "the pose did not move the decal in the image";
    EXPECT_GT(iou(projectedLater, splatLater), 0.9) << "the splat does not ride the skin";
}
