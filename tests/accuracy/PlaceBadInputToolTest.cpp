// spatter-place on bad input: every option given once with a value, decimal numbers, outputs that are
// neither inputs nor each other and can be written, files where files are read; each refused with
// exit code 2 and a message naming the problem, before any output is written.

#include "PlaceToolRun.hpp"
#include "TestData.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

using namespace spatter;

namespace {

// A wall (x in [-4, 4], y in [0, 4], z = 0) as OBJ and one ray that hits it, in `dir`.
struct PlaceInputs {
    std::string dir, scene, rays;
};

PlaceInputs writePlaceInputs(const std::string& name) {
    PlaceInputs in{test::scratchDir(name), "", ""};
    in.scene = in.dir + "/wall.obj";
    in.rays = in.dir + "/rays.txt";
    std::ofstream(in.scene) << "v -4 0 0\nv 4 0 0\nv 4 4 0\nv -4 4 0\nf 1 2 3\nf 1 3 4\n";
    std::ofstream(in.rays) << "0 1 5 0 0 -1\n";
    return in;
}

struct PlaceExit {
    int code = -1;      // the exit code
    std::string errors; // stderr
};

// spatter-place on the wall with its rays and `extra` options.
PlaceExit placeExit(const PlaceInputs& in, const std::string& extra) {
    const test::PlaceToolRun r =
        test::runPlaceTool("'" + in.scene + "' --rays '" + in.rays + "' " + extra, in.dir);
    return {WIFEXITED(r.status) ? WEXITSTATUS(r.status) : -1, test::readFile(in.dir + "/stderr.txt")};
}

} // namespace

TEST(PlaceTool, RefusesAnOutputThatIsItsInputOrAnotherOutput) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-same-file");
    const std::string scene = test::readFile(in.scene), rays = test::readFile(in.rays);
    PlaceExit r = placeExit(in, "--out '" + in.scene + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("SCENE and --out name the same file"), std::string::npos) << r.errors;
    r = placeExit(in, "--out '" + in.dir + "/../" + std::filesystem::path(in.dir).filename().string() +
                          "/rays.txt'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("--rays and --out name the same file"), std::string::npos) << r.errors;
    r = placeExit(in, "--save '" + in.rays + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(test::readFile(in.scene), scene);
    EXPECT_EQ(test::readFile(in.rays), rays);
    r = placeExit(in, "--out '" + in.dir + "/x.jsonl' --save '" + in.dir + "/./x.jsonl'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("--out and --save name the same file"), std::string::npos) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/x.jsonl"));
}

TEST(PlaceTool, ChecksEveryOutputBeforeWritingAny) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-outputs-first");
    const std::string out = " --out '" + in.dir + "/o1.jsonl'";
    PlaceExit r = placeExit(in, out + " --save '" + in.dir + "/no/such/folder/s.save'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("does not exist"), std::string::npos) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/o1.jsonl"));
    r = placeExit(in, out + " --save '" + in.dir + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("is a directory"), std::string::npos) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/o1.jsonl"));
    EXPECT_EQ(placeExit(in, out + " --save '" + in.dir + "/s.save'").code, 0);
    EXPECT_TRUE(std::filesystem::exists(in.dir + "/o1.jsonl"));
}

TEST(PlaceTool, RefusesADirectoryWhereItReadsAFileAndAFileForItsCache) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-directories");
    const std::string command = "'" + in.scene + "' --rays '" + in.dir + "'";
    const test::PlaceToolRun r = test::runPlaceTool(command, in.dir);
    EXPECT_EQ(WEXITSTATUS(r.status), 2);
    EXPECT_NE(test::readFile(in.dir + "/stderr.txt").find("is a directory"), std::string::npos);
    const PlaceExit cache = placeExit(in, "--proxy auto --cache '" + in.rays + "'");
    EXPECT_EQ(cache.code, 2);
    EXPECT_NE(cache.errors.find("--cache: " + in.rays + " is not a directory"), std::string::npos)
        << cache.errors;
}

TEST(PlaceTool, TakesAWholeSeedOfDigitsWithinSixtyFourBits) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-seed");
    for (const char* bad :
         {"99999999999999999999", "18446744073709551616", "' -1'", "' 1'", "+1", "1.0", "0x10"})
        EXPECT_EQ(placeExit(in, std::string("--seed ") + bad).code, 2) << bad;
    EXPECT_EQ(placeExit(in, "--seed 18446744073709551615").code, 0);
}

TEST(PlaceTool, RefusesAnOptionGivenTwiceOrWithoutItsValue) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-twice");
    const PlaceExit r = placeExit(in, "--seed 1 --seed 2");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.errors.find("--seed given twice"), std::string::npos) << r.errors;
    EXPECT_EQ(placeExit(in, "--summary --summary").code, 2);
    EXPECT_EQ(placeExit(in, "--out --summary").code, 2);
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/--summary"));
}

TEST(PlaceTool, ReadsNumbersAsDecimalTextOnly) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-decimal");
    for (const char* bad : {"--size 0x10", "--time 0x10", "--size ' 1'", "--size '1 '", "--max-angle inf",
                            "--translate 0,0,0x1", "--proxy 0x1%", "--proxy 1e300"})
        EXPECT_EQ(placeExit(in, bad).code, 2) << bad;
    EXPECT_EQ(placeExit(in, "--size 1e-1,.5 --time -0.5 --translate 0,-1.5e0,0").code, 0);
}

TEST(PlaceTool, RemovesItsRecordsWhenTheSaveFailsLate) {
    if (!test::kPlaceTool) GTEST_SKIP() << "spatter-place is not built";
    const PlaceInputs in = writePlaceInputs("place-late-failure");
    // The save's temporary file cannot be created: the save fails after the records are written.
    std::filesystem::create_directories(in.dir + "/s.save.tmp");
    const PlaceExit r = placeExit(in, "--out '" + in.dir + "/o1.jsonl' --save '" + in.dir + "/s.save'");
    EXPECT_EQ(r.code, 2);
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/o1.jsonl")) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(in.dir + "/s.save"));
}
