#include "spatter/core/SceneLoader.hpp"

#include "FifoWriter.hpp"
#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include <sys/stat.h>

using namespace spatter;
using ::testing::HasSubstr;

static std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

static void expectMesh(const std::string& path, size_t vertices, size_t triangles) {
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->objects.size(), 1u);
    const SceneObject& o = scene->objects[0];
    EXPECT_EQ(o.mesh->vertexCount(), vertices);
    EXPECT_EQ(o.mesh->triangleCount(), triangles);
    EXPECT_FALSE(o.dynamic);
    EXPECT_TRUE(o.receivesDecals);
    EXPECT_TRUE(validateMesh(*o.mesh).ok());
}

// Counts from ../shared/data/SOURCES.md.
TEST(MeshFileLoader, LoadsOpenBunnyWithEveryTriangleAndUnreferencedVertex) {
    SPATTER_REQUIRE_SHARED(path, "meshes/stanford-bunny.obj");
    expectMesh(path, 35947, 69451);
}

TEST(MeshFileLoader, LoadsFandisk) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    expectMesh(path, 6475, 12946);
}

TEST(MeshFileLoader, LoadsRockerArm) {
    SPATTER_REQUIRE_SHARED(path, "meshes/rocker-arm.obj");
    expectMesh(path, 10044, 20088);
}

TEST(MeshFileLoader, LoadsEachFormat) {
    const std::string dir = test::scratchDir("meshformats");
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    const std::string off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    expectMesh(writeFile(dir, "quad.obj", obj), 4, 2);
    expectMesh(writeFile(dir, "quad.off", off), 4, 2);
    expectMesh(writeFile(dir, "tri.ply", ply), 3, 1);
    expectMesh(writeFile(dir, "tri.stl", stl), 3, 1);
}

TEST(MeshFileLoader, RejectsMissingFile) {
    Result<Scene> scene = loadScene("/nonexistent/dir/mesh.obj");
    EXPECT_THAT(scene.error(), HasSubstr("not found"));
    EXPECT_THAT(scene.error(), HasSubstr("mesh.obj"));
}

TEST(MeshFileLoader, RejectsEmptyFile) {
    const std::string dir = test::scratchDir("meshempty");
    EXPECT_THAT(loadScene(writeFile(dir, "empty.obj", "")).error(), HasSubstr("empty"));
}

TEST(MeshFileLoader, RejectsFileWithoutFaces) {
    const std::string dir = test::scratchDir("meshnofaces");
    EXPECT_THAT(loadScene(writeFile(dir, "points.obj", "v 0 0 0\nv 1 0 0\n")).error(), HasSubstr("no faces"));
}

TEST(MeshFileLoader, RejectsUnparseablePositionInObj) {
    const std::string dir = test::scratchDir("meshnanobj");
    EXPECT_FALSE(loadScene(writeFile(dir, "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")).ok());
}

TEST(MeshFileLoader, RejectsNonFinitePositionInBinaryPly) {
    const std::string dir = test::scratchDir("meshnanply");
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    const uint8_t corners = 3;
    const int32_t face[3] = {0, 1, 2};
    bytes.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
    bytes.append(reinterpret_cast<const char*>(&corners), 1);
    bytes.append(reinterpret_cast<const char*>(face), sizeof(face));
    Result<Scene> scene = loadScene(writeFile(dir, "nan.ply", bytes));
    EXPECT_THAT(scene.error(), HasSubstr("not finite"));
}

TEST(MeshFileLoader, RejectsIndexPastVertexCount) {
    const std::string dir = test::scratchDir("meshindex");
    Result<Scene> scene = loadScene(writeFile(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
    EXPECT_FALSE(scene.ok());
}

// OpenMesh's OBJ reader skips a "v" line whose first three words do not read as floats, so that
// every later face index names the vertex after the one meant.
TEST(MeshFileLoader, RejectsAVertexLineThatIsNotThreeFiniteNumbers) {
    const std::string dir = test::scratchForTest("objvertex");
    auto error = [&](const std::string& vertex) {
        const std::string obj = "v 0 0 0\n" + vertex + "\nv 5 0 0\nv 0 5 0\nf 1 2 3\n";
        Result<Scene> scene = loadScene(writeFile(dir, "v.obj", obj));
        return scene ? std::string("loaded") : scene.error();
    };
    EXPECT_THAT(error("v nan nan nan"), HasSubstr("v.obj: line 2: vertex coordinate 'nan' is not finite"));
    EXPECT_THAT(error("v 0 -inf 0"), HasSubstr("line 2: vertex coordinate '-inf' is not finite"));
    EXPECT_THAT(error("v 1e999 0 0"), HasSubstr("line 2: vertex coordinate '1e999' is not finite"));
    EXPECT_THAT(error("v 0x10 0 0"), HasSubstr("line 2: vertex coordinate '0x10' is not a decimal number"));
    EXPECT_THAT(error("v 0 0 1abc"), HasSubstr("line 2: vertex coordinate '1abc' is not a decimal number"));
    EXPECT_THAT(error("v 1,5 0 0"), HasSubstr("line 2: vertex coordinate '1,5' is not a decimal number"));
    EXPECT_THAT(error("v 1 2"), HasSubstr("line 2: 'v' line has 2 numbers, 3 needed"));
    EXPECT_THAT(error("v 1 2 # z"), HasSubstr("line 2: 'v' line has 2 numbers, 3 needed"));
    // What iostreams read as numbers still loads: signs, bare points, exponents, a w, colours, and
    // magnitudes below float's range (read as 0).
    expectMesh(writeFile(dir, "fine.obj", "v +1. -.5 2E+1 1\nv 1e-50 0 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\n"), 3,
               1);
}

// A skipped "vn" line shifts every later normal; a "vt" line that is not numbers fails the whole read
// without saying where.
TEST(MeshFileLoader, RejectsANormalOrTextureCoordinateLineThatIsNotFiniteNumbers) {
    const std::string dir = test::scratchForTest("objattributes");
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_THAT(loadScene(writeFile(dir, "vn.obj", triangle + "vn nan 0 1\nf 1//1 2//1 3//1\n")).error(),
                HasSubstr("vn.obj: line 4: normal coordinate 'nan' is not finite"));
    EXPECT_THAT(loadScene(writeFile(dir, "vt.obj", triangle + "vt 0 inf\nf 1/1 2/1 3/1\n")).error(),
                HasSubstr("vt.obj: line 4: texture coordinate 'inf' is not finite"));
    EXPECT_THAT(loadScene(writeFile(dir, "vt1.obj", triangle + "vt 0\nf 1/1 2/1 3/1\n")).error(),
                HasSubstr("line 4: 'vt' line has 1 number, 2 needed"));
}

// OpenMesh's OBJ reader skips a corner that is no integer and then a face left with fewer than three
// different vertices, while the other faces load. A face of fewer than three different vertices has no
// area, so it may go.
TEST(MeshFileLoader, RejectsObjFacesTheReaderWouldDrop) {
    const std::string dir = test::scratchForTest("objfaces");
    auto error = [&](const std::string& face) {
        const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n" + face + "\n";
        Result<Scene> scene = loadScene(writeFile(dir, "f.obj", obj));
        return scene ? std::string("loaded") : scene.error();
    };
    EXPECT_THAT(error("f 1 2"), HasSubstr("f.obj: line 6: face has 2 corners, at least 3 needed"));
    EXPECT_THAT(error("f"), HasSubstr("line 6: face has 0 corners, at least 3 needed"));
    EXPECT_THAT(error("f a b c"), HasSubstr("line 6: face corner 'a' is not an integer vertex index"));
    EXPECT_THAT(error("f 1.5 2 4"), HasSubstr("line 6: face corner '1.5' is not an integer vertex index"));
    EXPECT_THAT(error("f 1 2 4x"), HasSubstr("line 6: face corner '4x' is not an integer vertex index"));
    EXPECT_THAT(error("f 1 2 99999999999"), HasSubstr("line 6: face corner '99999999999' refers to vertex "
                                                      "99999999999 of 4"));
    EXPECT_THAT(error("f 1 2 4294967297"), HasSubstr("refers to vertex 4294967297 of 4"));
    EXPECT_EQ(error("f 1 2 1"), "loaded");
    EXPECT_THAT(error("f 1/x 2 4"),
                HasSubstr("line 6: face corner '1/x': texture coordinate index 'x' is not"));
    EXPECT_THAT(error("f 1/1 2/1 4/1"),
                HasSubstr("line 6: face corner '1/1' refers to texture coordinate 1 of 0"));
    EXPECT_THAT(error("f 1//2 2//2 4//2"), HasSubstr("line 6: face corner '1//2' refers to normal 2 of 0"));
    EXPECT_THAT(error("f 1/1/1/1 2 4"), HasSubstr("line 6: face corner '1/1/1/1' has more than v/vt/vn"));
    EXPECT_EQ(error("f 1 2 4 # a comment"), "loaded");
}

// Faces may come before the vertices they name; of several corners past the last vertex the first
// one in the file is named.
TEST(MeshFileLoader, ChecksObjIndicesAgainstEveryVertexOfTheFile) {
    const std::string dir = test::scratchForTest("objforward");
    expectMesh(writeFile(dir, "ahead.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// -1// -2//\n"), 3, 2);
    EXPECT_THAT(
        loadScene(writeFile(dir, "past.obj", "f 1 2 5\nf 1 2 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"))
            .error(),
        HasSubstr("past.obj: line 1: face corner '5' refers to vertex 5 of 4"));
}

// The OBJ check reads the file in blocks: lines across a block's end, a line longer than a block, CR
// LF line ends and a last line without one are all read whole.
TEST(MeshFileLoader, ReadsObjLinesAcrossBlocksWhole) {
    const std::string dir = test::scratchForTest("objblocks");
    std::string obj = "# " + std::string(3u << 20, 'x') + "\r\n";
    for (int i = 0; i < 60000; ++i)
        obj += "v " + std::to_string(i) + ".25 " + std::to_string(i % 7) + " -" + std::to_string(i % 11) +
               "\r\n";
    for (int i = 1; i + 2 <= 60000; i += 3)
        obj += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\r\n";
    expectMesh(writeFile(dir, "blocks.obj", obj + "f 60000 2 1"), 60000, 20001);
    obj += "v 1 2 nan\r\n";
    EXPECT_THAT(loadScene(writeFile(dir, "late.obj", obj)).error(),
                HasSubstr("line 80002: vertex coordinate 'nan' is not finite"));
}

// OpenMesh's PLY and OFF readers skip a face with a corner past the vertices, a vertex twice or fewer
// than three corners, while the other faces load; a face of fewer than three different vertices has
// no area, so it may go.
TEST(MeshFileLoader, RejectsPlyAndOffFacesTheReaderWouldDrop) {
    const std::string dir = test::scratchForTest("plyofffaces");
    auto ply = [&](const std::string& face) {
        const std::string text =
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n" +
            face + "\n";
        Result<Scene> scene = loadScene(writeFile(dir, "f.ply", text));
        return scene ? std::string("loaded") : scene.error();
    };
    EXPECT_THAT(ply("3 0 1 99"), HasSubstr("f.ply: PLY face 1: corner 99 is not one of the 4 vertices"));
    EXPECT_THAT(ply("3 0 -1 3"), HasSubstr("PLY face 1: corner -1 is not one of the 4 vertices"));
    EXPECT_THAT(ply("4 0 0 3 1"), HasSubstr("PLY face 1 names vertex 0 twice"));
    EXPECT_EQ(ply("3 0 0 3"), "loaded");
    EXPECT_THAT(ply("2 0 3"), HasSubstr("PLY face 1 has 2 corners (at least 3"));
    EXPECT_THAT(ply("3 0 x 3"), HasSubstr("PLY face 1: 'x' is not an integer"));
    EXPECT_EQ(ply("4 0 1 3 2"), "loaded");

    std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int32_t corners[3] = {0, 1, -5};
    binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    binary += char(3);
    binary.append(reinterpret_cast<const char*>(corners), sizeof corners);
    EXPECT_THAT(loadScene(writeFile(dir, "neg.ply", binary)).error(),
                HasSubstr("PLY face 0: corner -5 is not one of the 3 vertices"));

    auto off = [&](const std::string& face) {
        const std::string text = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n" + face + "\n";
        Result<Scene> scene = loadScene(writeFile(dir, "f.off", text));
        return scene ? std::string("loaded") : scene.error();
    };
    EXPECT_THAT(off("3 0 1 7"), HasSubstr("f.off: OFF face 1: corner 7 is not one of the 4 vertices"));
    EXPECT_THAT(off("3 0 1 -1"), HasSubstr("OFF face 1: corner -1 is not one of the 4 vertices"));
    EXPECT_THAT(off("4 0 1 1 3"), HasSubstr("OFF face 1 names vertex 1 twice"));
    EXPECT_EQ(off("3 1 1 3"), "loaded");
    EXPECT_THAT(off("2 0 1"), HasSubstr("OFF face 1 has 2 corners (at least 3"));
    EXPECT_EQ(off("3 0 1 3"), "loaded");
}

// A coordinate that is no number fails every later read of OpenMesh's text PLY and OFF readers.
TEST(MeshFileLoader, NamesTheVertexOfANonFiniteCoordinateInTextPlyAndOff) {
    const std::string dir = test::scratchForTest("plyoffnan");
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n";
    EXPECT_THAT(loadScene(writeFile(dir, "nan.ply", ply)).error(),
                HasSubstr("nan.ply: PLY vertex 1: y 'nan' is not finite"));
    EXPECT_THAT(
        loadScene(writeFile(dir, "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 1e999\n0 1 0\n3 0 1 2\n")).error(),
        HasSubstr("nan.off: OFF vertex 1: coordinate '1e999' is not finite"));
}

// OpenMesh's OFF reader reads a count of -3 as 4294967293 and ignores counts on the "OFF" line.
TEST(MeshFileLoader, RejectsOffCountsThatAreNegativeOrOnTheHeaderLine) {
    const std::string dir = test::scratchForTest("offcounts");
    EXPECT_THAT(loadScene(writeFile(dir, "neg.off", "OFF\n-3 1 0\n0 0 0\n")).error(),
                HasSubstr("neg.off: OFF header: the vertex count -3 is negative"));
    EXPECT_THAT(loadScene(writeFile(dir, "line.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).error(),
                HasSubstr("OFF header: the reader ignores the rest of the line 'OFF 3 1 0'"));
}

// OpenMesh's STL reader takes a binary file with a wrong triangle count as ASCII (no facets), reads
// an ASCII coordinate that is no number as 0, ignores a fourth vertex, and merges binary corners
// through a map that NaN leaves without order.
TEST(MeshFileLoader, RejectsStlFacetsTheReaderWouldMisread) {
    const std::string dir = test::scratchForTest("stlfacets");
    auto ascii = [&](const std::string& loop) {
        const std::string text =
            "solid t\nfacet normal 0 0 1\nouter loop\n" + loop + "endloop\nendfacet\nendsolid t\n";
        Result<Scene> scene = loadScene(writeFile(dir, "a.stl", text));
        return scene ? std::string("loaded") : scene.error();
    };
    EXPECT_THAT(ascii("vertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\n"),
                HasSubstr("a.stl: line 4: vertex coordinate 'nan' is not finite"));
    EXPECT_THAT(ascii("vertex 0 0 0\nvertex abc 0 0\nvertex 0 1 0\n"),
                HasSubstr("line 5: vertex coordinate 'abc' is not a decimal number"));
    EXPECT_THAT(ascii("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 5 5 5\n"),
                HasSubstr("line 7: facet has more than 3 vertices"));
    EXPECT_THAT(ascii("vertex 0 0 0\nvertex 1 0 0\n"), HasSubstr("line 6: facet has fewer than 3 vertices"));
    EXPECT_THAT(ascii("vertex 0 0 0\nvertex 1 0\nvertex 0 1 0\n"),
                HasSubstr("line 5: vertex has 2 coordinates"));
    EXPECT_EQ(ascii("  VERTEX 0 0 0\r\nvertex 1 0 0\nvertex 0 1 0\n"), "loaded");
    EXPECT_THAT(
        loadScene(writeFile(dir, "cut.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"))
            .error(),
        HasSubstr("ASCII STL ends inside a facet"));

    auto binary = [&](const std::string& header, uint32_t count, const std::vector<float>& corners) {
        std::string bytes = header;
        bytes.resize(80, '\0');
        bytes.append(reinterpret_cast<const char*>(&count), 4);
        for (size_t t = 0; t + 9 <= corners.size(); t += 9) {
            const float normal[3] = {0, 0, 1};
            bytes.append(reinterpret_cast<const char*>(normal), sizeof normal);
            bytes.append(reinterpret_cast<const char*>(&corners[t]), 9 * sizeof(float));
            bytes.append(2, '\0');
        }
        Result<Scene> scene = loadScene(writeFile(dir, "b.stl", bytes));
        return scene ? std::string("loaded") : scene.error();
    };
    const std::vector<float> two = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    EXPECT_EQ(binary("solid but binary", 2, two), "loaded");
    EXPECT_THAT(binary("", 3, two),
                HasSubstr("b.stl: binary STL: the header counts 3 triangles, which take 234 "
                          "bytes, but the file has 184"));
    std::vector<float> nan = two;
    nan[10] = NAN;
    EXPECT_THAT(binary("", 2, nan), HasSubstr("binary STL triangle 1: corner 0 (1, nan, 0) is not finite"));
}

// OpenMesh's OBJ reader opens and reads the material library an "mtllib" line names, beside the file:
// a FIFO waits for a writer, a device such as /dev/zero never ends. Missing ones it skips.
TEST(MeshFileLoader, RejectsAnObjMaterialLibraryThatIsNotARegularFile) {
    const std::string dir = test::scratchForTest("objmtllib");
    ASSERT_EQ(mkfifo((dir + "/pipe.mtl").c_str(), 0644), 0);
    test::FifoWriter writer(dir + "/pipe.mtl");
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    EXPECT_THAT(
        loadScene(writeFile(dir, "pipe.obj", "mtllib pipe.mtl\n" + triangle)).error(),
        HasSubstr(
            "pipe.obj: line 1: material library 'pipe.mtl' is a FIFO (named pipe), not a regular file"));
    expectMesh(writeFile(dir, "missing.obj", "mtllib missing.mtl\n" + triangle), 3, 1);
}

// writeObj's file reads back to the same positions (to the float bit), triangles and normals, after
// its comment line; a comment of two lines is refused before anything is written.
TEST(MeshFileLoader, ReadsBackWhatWriteObjWrote) {
    const std::string dir = test::scratchDir("writeobj");
    Mesh m;
    m.positions = {{0.1f, 0.0f, 1e-7f}, {1.0f / 3.0f, 0.0f, 0.0f}, {0.0f, 2.0f / 3.0f, 0.0f}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.indices = {0, 1, 2};
    const std::string path = dir + "/written.obj";
    ASSERT_TRUE(writeObj(m, path, "three vertices"));
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first, "# three vertices");
    Result<Scene> back = loadScene(path);
    ASSERT_TRUE(back) << back.error();
    ASSERT_EQ(back->objects.size(), 1u);
    const Mesh& read = *back->objects[0].mesh;
    EXPECT_EQ(read.positions, m.positions);
    EXPECT_EQ(read.indices, m.indices);
    ASSERT_EQ(read.normals.size(), 3u);
    EXPECT_EQ(read.normals[2], m.normals[2]);

    const std::string refused = dir + "/refused.obj";
    Status twoLines = writeObj(m, refused, "one\ntwo");
    ASSERT_FALSE(twoLines);
    EXPECT_THAT(twoLines.error(), HasSubstr("more than one line"));
    EXPECT_FALSE(std::ifstream(refused).good());
}
