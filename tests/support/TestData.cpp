#include "TestData.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <unistd.h>
#include <vector>

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

namespace {

// The scratch directories this process made: removed when it exits after every test passed, kept
// (their names carry the process id) for a look at what a failing test wrote.
class ScratchRegistry {
public:
    void add(const fs::path& dir) {
        std::lock_guard<std::mutex> lock(mutex_);
        dirs_.push_back(dir);
    }
    ~ScratchRegistry() {
        if (!::testing::UnitTest::GetInstance()->Passed()) return;
        std::error_code ec;
        for (const fs::path& dir : dirs_)
            fs::remove_all(dir, ec);
    }

private:
    std::mutex mutex_;
    std::vector<fs::path> dirs_;
};

ScratchRegistry& scratchRegistry() {
    static ScratchRegistry registry;
    return registry;
}

} // namespace

std::string scratchDir(const std::string& name) {
    fs::path p = fs::temp_directory_path() / ("spatter-test-" + name + "-" + std::to_string(getpid()));
    std::error_code ec;
    fs::remove_all(p, ec);
    fs::create_directories(p);
    scratchRegistry().add(p);
    return p.string();
}

std::string scratchForTest(const std::string& prefix) {
    return scratchDir(prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

} // namespace spatter::test
