#pragma once
// GltfLoading: loading the glTF files the tests write, for the tests that expect a scene and those
// that expect a refusal.

#include "spatter/core/Scene.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace spatter::test {

// The scene of `path`, or an empty one and a test failure when it does not load.
inline Scene loaded(const std::string& path) {
    Result<Scene> scene = loadGltf(path);
    EXPECT_TRUE(scene.ok()) << scene.error();
    return scene.ok() ? std::move(scene.value()) : Scene{};
}

// The error loading `path` gives (which names the file), or "" and a test failure when it loads.
inline std::string rejection(const std::string& path) {
    Result<Scene> scene = loadGltf(path);
    if (scene.ok()) {
        ADD_FAILURE() << path << " loaded but should have been rejected";
        return "";
    }
    EXPECT_THAT(scene.error(), ::testing::HasSubstr(path));
    return scene.error();
}

} // namespace spatter::test
