#pragma once
// Access to the third-party test data in ../shared/data, which is never copied into the project.

#include <string>

namespace spatter::test {

// Directory of the shared data (SPATTER_SHARED_DATA overrides the default ../shared/data).
std::string sharedDataDir();

// Full path of `relative` inside the shared data. When the data is absent the calling test is
// skipped with a message, except under CI=true, where it fails: there the data must be present.
std::string sharedDataPath(const std::string& relative);

// A fresh empty directory under the system temp dir for files a test writes (unique per process),
// removed when the process exits with every test passed.
std::string scratchDir(const std::string& name);
// scratchDir of `prefix` followed by the running test's name.
std::string scratchForTest(const std::string& prefix);

// True under CI=true, where shared data must be present.
bool runningInCi();

} // namespace spatter::test

// Use at the top of a test: binds `var` to the file's path or skips/fails the test.
#define SPATTER_REQUIRE_SHARED(var, relative)                                                                \
    const std::string var = ::spatter::test::sharedDataPath(relative);                                       \
    if (var.empty()) {                                                                                       \
        if (::spatter::test::runningInCi()) FAIL() << "CI=true but shared data is missing: " << relative;    \
        GTEST_SKIP() << "shared data not found (" << relative << "); set SPATTER_SHARED_DATA";               \
    }
