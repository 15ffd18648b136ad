#include "TestData.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;

namespace spatter::test {

std::string sharedDataDir() {
    if (const char* env = std::getenv("SPATTER_SHARED_DATA"); env && *env) return env;
    return SPATTER_DEFAULT_SHARED_DATA;
}

bool runningInCi() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

std::string sharedDataPath(const std::string& relative) {
    fs::path p = fs::path(sharedDataDir()) / relative;
    std::error_code ec;
    return fs::exists(p, ec) ? p.lexically_normal().string() : std::string();
}

std::string scratchDir(const std::string& name) {
    fs::path p = fs::temp_directory_path() / ("spatter-test-" + name + "-" + std::to_string(getpid()));
    std::error_code ec;
    fs::remove_all(p, ec);
    fs::create_directories(p);
    return p.string();
}

std::string scratchForTest(const std::string& prefix) {
    return scratchDir(prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

} // namespace spatter::test
