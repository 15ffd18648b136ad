#pragma once
// What the tests of the example hosts (apps/examples) share: running a host as a separate process on
// a scene with decals, and the checks every host and path is held to: its coverage view against the
// CPU reference (rays through every pixel centre, the projector's inclusion rule in double
// precision) with an IoU of 0.99, and its albedo under the decals against spatter-render's.

#include "RenderTestSupport.hpp"
#include "TestData.hpp"
#include "ToolGl.hpp"

#include "spatter/core/Image.hpp"
#include "spatter/render/Camera.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace spatter::test {

// A host under test: its program and the switches that pick its path (e.g. --dbuffer).
struct ExampleHost {
    const char* tool = nullptr;
    std::vector<std::string> switches;
    std::string name; // names its scratch files
};

// Runs `tool` with `args`, its output discarded; returns its exit code (-1 when it did not exit
// normally).
int runTool(const char* tool, const std::vector<std::string>& args);

// A scratch directory for the example tests' files.
std::string exampleScratch();

// The host's image of `view` ("final", "albedo" or "coverage") for the scene and decal options
// `args`, seen by `camera` at the tests' small size; empty when it failed, which fails the test.
Image runExample(const ExampleHost& host, const std::vector<std::string>& args, const Camera& camera,
                 const std::string& view, const std::string& name);

// The host's coverage view matches the CPU reference with an IoU of at least 0.99, on the gallery
// with rays from the camera, on the Stanford bunny, fandisk and DamagedHelmet with spatter-place's
// records (skipped without the shared data), with the camera inside a decal box (half-depth 3 m),
// 1 m in front of its decal, and where the decals' boxes reach through an object that takes no
// decals.
void expectCoverageOnTheGallery(const ExampleHost& host);
void expectCoverageOnSharedScenes(const ExampleHost& host);
void expectCoverageWithTheCameraInsideADecalBox(const ExampleHost& host);
void expectCoverageWithAnObjectThatTakesNoDecals(const ExampleHost& host);

// The host's albedo view against spatter-render's on the same decals (60 rays at the gallery's wall of
// targets), at the pixels both cover, in linear terms and units of 1/255; fails the test when they
// cover too few pixels to compare.
struct AlbedoAgreement {
    size_t pixels = 0;
    double mean = 0.0;         // over the pixels and channels
    double percentile99 = 0.0; // of the pixels' largest channel difference
    double largest = 0.0;
};
AlbedoAgreement albedoAgainstSpatterRender(const ExampleHost& host);

} // namespace spatter::test
