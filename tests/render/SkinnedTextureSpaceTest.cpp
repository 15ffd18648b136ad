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

#include <initializer_list>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr int kSplatView = 160;

// builtin:skinned-arm with its round bar (whose lathe UVs wrap) replaced by sheets of the same
// length in the XY plane at the depths `z`, facing +Z, each with its own UV chart side by side in the
// unit square, skinned as the bar is.
Scene skinnedSheets(const std::vector<float>& z) {
    Scene scene = makeSkinnedArm();
    std::vector<float> across, along;
    for (int i = 0; i <= 12; ++i)
        across.push_back(float(i) / 12.0f);
    for (int i = 0; i <= 40; ++i)
        along.push_back(float(i) / 40.0f);
    Mesh sheets;
    for (size_t k = 0; k < z.size(); ++k) {
        glm::mat4 toArm(1.0f); // grid (x, 0, y) to (0.3 x - 0.15, 1 - y, z[k])
        toArm[0] = glm::vec4(0.3f, 0.0f, 0.0f, 0.0f);
        toArm[1] = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
        toArm[2] = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);
        toArm[3] = glm::vec4(-0.15f, 1.0f, z[k], 1.0f);
        Mesh sheet = makeGrid(across, along);
        for (glm::vec2& uv : sheet.uvs)
            uv.x = (float(k) + uv.x) / float(z.size());
        appendMesh(sheets, sheet, toArm);
    }
    SceneObject& o = scene.objects[0];
    SceneObject made = makeSceneObject("sheets", sheets, o.transform, true);
    made.node = o.node;
    made.skin = o.skin;
    made.skinWeights.influences = 2;
    for (const glm::vec3& p : sheets.positions) {
        const double w = skinnedArmElbowWeight(double(p.y), double(SkinnedArmSettings{}.length));
        made.skinWeights.joints.insert(made.skinWeights.joints.end(), {0, 1});
        made.skinWeights.weights.insert(made.skinWeights.weights.end(), {1.0 - w, w});
    }
    o = std::move(made);
    return scene;
}

// An opaque square, so that a splat's coverage (where its texture shows) is the decal's footprint.
Image opaqueSquare() {
    Image opaque;
    opaque.width = opaque.height = 16;
    opaque.rgba.assign(16 * 16 * 4, 255);
    return opaque;
}

// A renderer of `scene` drawing decals of `type` with opaque texture, object 0 in texture space.
Result<Renderer> splatRenderer(const Scene& scene, DecalType& type, uint8_t objectId, bool textureSpace) {
    Result<Renderer> r = makeRenderer(kSplatView, kSplatView);
    if (!r) return r;
    if (Status s = r->setScene(scene); !s) return fail(s.error());
    Result<int> layer = r->addDecalTexture(opaqueSquare());
    if (!layer) return fail(layer.error());
    type.texture = layer.value();
    r->setDecalTypes({type});
    if (Status s = r->setObjectIds({objectId}); !s) return fail(s.error());
    if (textureSpace)
        if (Status s = r->setObjectDecalMode(0, DecalMode::TextureSpace, 512); !s) return fail(s.error());
    return r;
}

struct ArmRig {
    Scene scene;
    SceneEvaluator evaluator;
    DecalType type;

    explicit ArmRig(const std::vector<float>& sheets) : scene(skinnedSheets(sheets)), evaluator(scene) {
        type.name = "mark";
        type.size = glm::vec2(0.12f);
        type.randomRotation = false;
        type.normalMap = false;
    }

    Status pose(double t, DecalSystem& system, std::initializer_list<Renderer*> renderers) {
        evaluator.evaluate(0, t);
        auto moved = system.setPose(0, evaluator.objectTransform(0), evaluator.jointMatrices(0), {});
        if (!moved) return fail(moved.error());
        for (Renderer* r : renderers)
            if (Status s = r->setPose(evaluator); !s) return s;
        return {};
    }

    // A point on the front sheet's forearm, as posed.
    glm::dvec3 forearm() const {
        return glm::dvec3(evaluator.jointMatrices(0)[1] * glm::dvec4(0.0, 0.75, 0.0, 1.0));
    }

    // A shot at the forearm from the front (+Z).
    SpawnResult shootForearm(DecalSystem& system, uint16_t decalType) const {
        Ray shot;
        shot.origin = forearm() + glm::dvec3(0.0, 0.0, 2.0);
        shot.direction = glm::dvec3(0.0, 0.0, -1.0);
        return system.spawn(shot, decalType);
    }
};

} // namespace

TEST(SkinnedTextureSpace, SplatMadeInTheDrawnPoseRidesTheSkinToAnotherPose) {
    SPATTER_REQUIRE_GL(gl);
    ArmRig rig({0.0f});
    Result<DecalSystem> system = DecalSystem::create(rig.scene);
    ASSERT_TRUE(system.ok()) << system.error();
    const uint16_t type = system->registerType(rig.type).value();
    Result<Renderer> projected = splatRenderer(rig.scene, rig.type, system->objectId(0), false);
    Result<Renderer> splatted = splatRenderer(rig.scene, rig.type, system->objectId(0), true);
    ASSERT_TRUE(projected.ok()) << projected.error();
    ASSERT_TRUE(splatted.ok()) << splatted.error();

    // Bent at the elbow (a quarter of the cycle), shot at the forearm from the front.
    ASSERT_TRUE(rig.pose(0.5, system.value(), {&projected.value(), &splatted.value()}).ok());
    const SpawnResult placed = rig.shootForearm(system.value(), type);
    ASSERT_TRUE(placed.placed()) << placed.reason;
    const glm::dvec3 forearm = rig.forearm();
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
    ASSERT_TRUE(rig.pose(0.2, system.value(), {&projected.value(), &splatted.value()}).ok());
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

TEST(SkinnedTextureSpace, ADeepSplatOnTheFrontSheetLeavesTheSheetBehindItClean) {
    SPATTER_REQUIRE_GL(gl);
    // Two sheets a quarter of a metre apart, posed as one skinned object: the back one stands for the
    // torso behind an arm. The type's depth reaches far past it.
    ArmRig rig({0.0f, -0.25f});
    rig.type.halfDepth = 2.0f;
    Result<DecalSystem> system = DecalSystem::create(rig.scene);
    ASSERT_TRUE(system.ok()) << system.error();
    const uint16_t type = system->registerType(rig.type).value();
    Result<Renderer> r = splatRenderer(rig.scene, rig.type, system->objectId(0), true);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(rig.pose(0.5, system.value(), {&r.value()}).ok());
    const SpawnResult placed = rig.shootForearm(system.value(), type);
    ASSERT_TRUE(placed.placed()) << placed.reason;
    const glm::dvec3 forearm = rig.forearm();
    const Camera front = lookAt(forearm + glm::dvec3(0.0, 0.0, 0.8), forearm);
    const Camera back = lookAt(forearm - glm::dvec3(0.0, 0.0, 1.0), forearm); // sees the back sheet

    r->setDecals({*system->get(placed.handle)});
    EXPECT_GT(countSet(whiteMask(renderView(r.value(), front, View::Coverage))), 150u);
    EXPECT_EQ(countSet(whiteMask(renderView(r.value(), back, View::Coverage))), 0u)
        << "the splat on the front sheet reached the sheet behind it";

    // The same decal with the type's depth, as an engine attaches one, paints the back sheet.
    Decal deepBox = *system->get(placed.handle);
    deepBox.halfDepth = rig.type.halfDepth;
    ASSERT_TRUE(r->clearObjectDecals(0).ok());
    r->setDecals({deepBox});
    EXPECT_GT(countSet(whiteMask(renderView(r.value(), back, View::Coverage))), 50u);
}
