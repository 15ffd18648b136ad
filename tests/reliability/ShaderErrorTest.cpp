// A shader that fails to compile must be reported with its file and line. The library's shader
// builder (render/src/ShaderProgram.cpp) builds test shaders (shaders/) here, embedded like the real
// ones; the driver's log names source strings by number, and the message maps the
// numbers to file names.

#include "ShaderProgram.hpp"
#include "ShaderSources.hpp"

#include "TestData.hpp"

#include "spatter/render/GlContext.hpp"

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <utility>

using namespace spatter;
using namespace spatter::render_detail;

namespace {

// The (file, line) pairs the error message points at: the driver's "S:L(" (Mesa) or "S(L)" (NVIDIA)
// references, with source string S looked up in the message's "S = file" list.
std::set<std::pair<std::string, int>> reportedLocations(const std::string& message) {
    std::map<int, std::string> files;
    const std::regex entry(R"((\d+) = ([A-Za-z0-9_.]+))");
    for (auto it = std::sregex_iterator(message.begin(), message.end(), entry); it != std::sregex_iterator();
         ++it)
        files[std::stoi((*it)[1])] = (*it)[2];
    std::set<std::pair<std::string, int>> where;
    const std::regex location(R"((?:^|\n)\s*(?:ERROR: )?(\d+)(?::(\d+)\(|\((\d+)\)))");
    for (auto it = std::sregex_iterator(message.begin(), message.end(), location);
         it != std::sregex_iterator(); ++it) {
        const int source = std::stoi((*it)[1]);
        const int line = std::stoi((*it)[2].matched ? (*it)[2].str() : (*it)[3].str());
        if (files.count(source)) where.insert({files[source], line});
    }
    return where;
}

class ShaderErrors : public ::testing::Test {
protected:
    void SetUp() override {
        Result<GlContext> gl = GlContext::createHeadless();
        if (!gl) {
            if (test::runningInCi()) FAIL() << "CI=true but no headless GL context: " << gl.error();
            GTEST_SKIP() << "no headless OpenGL 4.5 context (" << gl.error() << ")";
        }
        context_.emplace(std::move(gl).value());
    }
    std::optional<GlContext> context_;
};

} // namespace

TEST_F(ShaderErrors, CompileErrorNamesTheFileAndLine) {
    Result<GlProgram> program =
        buildProgram(shaderLibrary(kShaderSources), {{GL_FRAGMENT_SHADER, "broken.frag"}}, {});
    ASSERT_FALSE(program.ok());
    const std::string& message = program.error();
    EXPECT_NE(message.find("shader broken.frag does not compile"), std::string::npos) << message;
    const auto where = reportedLocations(message);
    EXPECT_TRUE(where.count({"broken.frag", 7})) << message;
}

TEST_F(ShaderErrors, ErrorInAnIncludedFileNamesThatFileAndLine) {
    Result<GlProgram> program =
        buildProgram(shaderLibrary(kShaderSources), {{GL_FRAGMENT_SHADER, "uses_broken_lib.frag"}}, {});
    ASSERT_FALSE(program.ok());
    const std::string& message = program.error();
    EXPECT_NE(message.find("shader uses_broken_lib.frag does not compile"), std::string::npos) << message;
    const auto where = reportedLocations(message);
    EXPECT_TRUE(where.count({"broken_lib.glsl", 3})) << message;
}

TEST_F(ShaderErrors, MissingFileIsNamed) {
    Result<GlProgram> program =
        buildProgram(shaderLibrary(kShaderSources), {{GL_FRAGMENT_SHADER, "absent.frag"}}, {});
    ASSERT_FALSE(program.ok());
    EXPECT_NE(program.error().find("absent.frag"), std::string::npos) << program.error();
}
