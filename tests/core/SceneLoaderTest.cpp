#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include <sys/stat.h>

using namespace spatter;
using ::testing::HasSubstr;

TEST(SceneLoader, RejectsUnknownExtensionNamingIt) {
    Result<Scene> scene = loadScene("level.fbx");
    EXPECT_THAT(scene.error(), HasSubstr("level.fbx"));
    EXPECT_THAT(scene.error(), HasSubstr(".fbx"));
}

TEST(SceneLoader, RejectsUnknownBuiltin) {
    EXPECT_THAT(loadScene("builtin:nothing").error(), HasSubstr("unknown builtin"));
}

TEST(SceneLoader, LoadsBuiltinGalleryAndRecordsSource) {
    Result<Scene> scene = loadScene("builtin:gallery");
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_EQ(scene->source, "builtin:gallery");
    EXPECT_GT(scene->triangleCount(), 10000u);
    EXPECT_GT(scene->dynamicObjectCount(), 0u);
    EXPECT_TRUE(validateScene(scene.value()).ok());
}

TEST(SceneLoader, TranslateMovesEveryObjectInDoublePrecision) {
    Scene scene;
    scene.objects.resize(2);
    scene.objects[1].transform[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
    scene.translate(glm::dvec3(1e6, 0.5, -1e6));
    EXPECT_EQ(scene.objects[0].transform[3], glm::dvec4(1e6, 0.5, -1e6, 1.0));
    EXPECT_EQ(scene.objects[1].transform[3], glm::dvec4(1e6 + 1.0, 2.5, 3.0 - 1e6, 1.0));
}

TEST(SceneLoader, ValidateSceneRejectsNonFiniteAndProjectiveTransformsButTakesSingularOnes) {
    Scene scene;
    SceneObject o;
    o.name = "flat";
    Mesh& flat = o.editMesh();
    flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    flat.indices = {0, 1, 2};
    computeNormals(flat);
    o.transform = glm::dmat4(0.0);
    scene.objects.push_back(o);
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("object 0 (flat): transform is not affine"));
    scene.objects[0].transform = glm::dmat4(1.0);
    scene.objects[0].transform[3][1] = std::numeric_limits<double>::infinity();
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("transform is not finite"));
    scene.objects[0].transform = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 1.0, 0.0)); // hides the node
    EXPECT_TRUE(validateScene(scene).ok());
}

TEST(SceneLoader, ValidateSceneRejectsMissingMaterial) {
    Scene scene;
    SceneObject o;
    Mesh& m = o.editMesh();
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    m.submeshes = {{0, 3, 4}};
    computeNormals(m);
    scene.objects.push_back(o);
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("material 4"));
}

TEST(SceneLoader, ValidateSceneRejectsAnObjectWithoutAMesh) {
    Scene scene;
    scene.objects.push_back(makeSceneObject("shared", makeBox(glm::vec3(1.0f), 1)));
    scene.objects.push_back(makeSceneObject("copy", scene.objects[0].mesh));
    EXPECT_TRUE(validateScene(scene).ok());
    scene.objects[1].mesh.reset();
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("object 1 (copy): has no render mesh"));
}

// Opening a FIFO waits for a writer; a directory has nothing to read. Neither is "not found".
TEST(SceneLoader, SaysWhatAScenePathThatIsNotARegularFileIs) {
    const std::string dir = test::scratchForTest("notregular");
    for (const std::string ext : {".obj", ".ply", ".off", ".stl", ".gltf", ".glb"}) {
        const std::string folder = dir + "/folder" + ext, pipe = dir + "/pipe" + ext;
        ASSERT_EQ(mkdir(folder.c_str(), 0755), 0);
        ASSERT_EQ(mkfifo(pipe.c_str(), 0644), 0);
        EXPECT_THAT(loadScene(folder).error(), HasSubstr("folder" + ext + ": is a directory"));
        EXPECT_THAT(loadScene(pipe).error(),
                    HasSubstr("pipe" + ext + ": is a FIFO (named pipe), not a regular file"));
        EXPECT_THAT(loadScene(dir + "/missing" + ext).error(),
                    HasSubstr("missing" + ext + ": file not found"));
    }
}
