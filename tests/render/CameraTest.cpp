#include "spatter/render/Camera.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;

TEST(Camera, ParsesTheToolSyntaxWithDefaults) {
    Result<Camera> c = parseCamera("eye=1,2,3;target=0,1.5,-4");
    ASSERT_TRUE(c.ok()) << c.error();
    EXPECT_EQ(c->eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(c->target, glm::dvec3(0, 1.5, -4));
    EXPECT_EQ(c->up, glm::dvec3(0, 1, 0));
    EXPECT_EQ(c->fovYDeg, 60.0);

    Result<Camera> d = parseCamera(" fov=45 ; up=0,0,1;target=1e3,0,0 ;eye=-2.5,0,0.5 ");
    ASSERT_TRUE(d.ok()) << d.error();
    EXPECT_EQ(d->fovYDeg, 45.0);
    EXPECT_EQ(d->up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(d->target.x, 1000.0);

    Result<Camera> round = parseCamera(formatCamera(d.value()));
    ASSERT_TRUE(round.ok()) << round.error();
    EXPECT_EQ(round->eye, d->eye);
    EXPECT_EQ(round->fovYDeg, d->fovYDeg);
}

TEST(Camera, RejectsMalformedCameraStrings) {
    const char* bad[] = {
        "target=0,0,0",                     // no eye
        "eye=0,0,1",                        // no target
        "eye=0,0,1;target=0,0,0;zoom=2",    // unknown key
        "eye=0,0;target=0,0,0",             // two components
        "eye=0,0,x;target=0,0,0",           // not a number
        "eye=0,0,1;target=0,0,0;fov=180",   // fov out of range
        "eye=0,0,1;target=0,0,0;fov=nan",   // NaN
        "eye=0,0,1;target=0,0,1",           // eye == target
        "eye=0,1,0;target=0,0,0",           // up parallel to the view
        "eye=0,0,1;target=0,0,0;up=0,0,0",  // zero up
        "eye=inf,0,1;target=0,0,0",         // infinite
        "eye=0,0,1;eye=0,0,2;target=0,0,0", // twice
        "eye",                              // no '='
        "eye=0x1,0,1;target=0,0,0",         // hexadecimal
    };
    for (const char* s : bad) {
        Result<Camera> c = parseCamera(s);
        EXPECT_FALSE(c.ok()) << s;
        if (!c.ok()) {
            EXPECT_EQ(c.error().rfind("camera:", 0), 0u) << c.error();
        }
    }
}

TEST(Camera, PixelCentreRaysProjectToPixelCentres) {
    Camera c;
    c.eye = {3.0, 2.0, 5.0};
    c.target = {-1.0, 0.5, -2.0};
    c.fovYDeg = 50.0;
    const int w = 160, h = 90;
    const glm::dmat4 vp = projection(c, double(w) / h) * viewRotation(c);
    for (int j : {0, 17, 89})
        for (int i : {0, 80, 159}) {
            const glm::dvec3 d = pixelDirection(c, w, h, i, j);
            EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
            const glm::dvec4 clip = vp * glm::dvec4(d * 7.0, 1.0);
            const double x = clip.x / clip.w, y = clip.y / clip.w;
            // Window coordinates with row 0 at the top.
            EXPECT_NEAR((x * 0.5 + 0.5) * w, i + 0.5, 1e-9);
            EXPECT_NEAR((0.5 - y * 0.5) * h, j + 0.5, 1e-9);
        }
}

TEST(Camera, ProjectionIsReversedZ) {
    Camera c;
    c.nearPlane = 0.1;
    const glm::dmat4 p = projection(c, 1.5);
    auto depth = [&](double dist) {
        const glm::dvec4 clip = p * glm::dvec4(0.0, 0.0, -dist, 1.0);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(depth(0.1), 1.0, 1e-12);
    EXPECT_NEAR(depth(1.0), 0.1, 1e-12);
    EXPECT_GT(depth(1e6), 0.0);
    EXPECT_LT(depth(1e6), 1e-6);

    c.farPlane = 100.0;
    const glm::dmat4 pf = projection(c, 1.5);
    const glm::dvec4 farClip = pf * glm::dvec4(0.0, 0.0, -100.0, 1.0);
    EXPECT_NEAR(farClip.z / farClip.w, 0.0, 1e-12);
    const glm::dvec4 nearClip = pf * glm::dvec4(0.0, 0.0, -0.1, 1.0);
    EXPECT_NEAR(nearClip.z / nearClip.w, 1.0, 1e-12);
}

TEST(Camera, NearPlaneRadiusReachesTheNearPlaneCorners) {
    Camera c;
    c.nearPlane = 0.2;
    c.fovYDeg = 90.0;
    const double aspect = 2.0;
    // Corner of the near rectangle: (near * tan * aspect, near * tan, -near), tan(45 deg) = 1.
    const double expected = std::sqrt(0.4 * 0.4 + 0.2 * 0.2 + 0.2 * 0.2);
    EXPECT_NEAR(nearPlaneRadius(c, aspect), expected, 1e-12);
}

// Planes the float projection cannot hold, and the smallest near plane and field of view, are refused.
TEST(Camera, RefusesPlanesAndAnglesTheFloatProjectionCannotHold) {
    Camera c = parseCamera("eye=0,0,1;target=0,0,0").value();
    ASSERT_TRUE(validateCamera(c).ok());
    Camera far = c;
    far.nearPlane = 1e300;
    EXPECT_FALSE(validateCamera(far).ok());
    far = c;
    far.farPlane = 2.0 * kMaxPlaneDistance;
    EXPECT_FALSE(validateCamera(far).ok());
    far.farPlane = kMaxPlaneDistance;
    EXPECT_TRUE(validateCamera(far).ok());
    Camera narrow = c;
    narrow.fovYDeg = 0.5 * kMinFovDeg;
    EXPECT_FALSE(validateCamera(narrow).ok());
    Camera near = c;
    near.nearPlane = 0.5 * kMinNearPlane;
    EXPECT_FALSE(validateCamera(near).ok());
}
