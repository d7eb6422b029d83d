// Camera::look_at and Camera::resized, checked against hand-computed projections.
#include <gtest/gtest.h>

#include <cmath>

#include "vksplat/camera/camera.hpp"
#include "vksplat/error.hpp"

namespace vksplat {
namespace {

// Continuous image coordinates of a world point (principal point convention of camera.hpp).
glm::dvec2 image_point(const Camera& camera, const glm::dvec3& world) {
    const glm::dvec3 p = camera.to_camera(world);
    return {camera.fx * p.x / p.z + camera.cx, camera.fy * p.y / p.z + camera.cy};
}

// The lego tiled benchmark camera of shared/data/README.md.
Camera benchmark_camera() {
    return Camera::look_at({0.0, -9.0, 7.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 1920, 1080, 1400.0, 1400.0);
}

TEST(LookAt, BenchmarkCameraAxesAreHandComputed) {
    const Camera camera = benchmark_camera();
    const double n = std::sqrt(130.0);  // |(0, 9, -7)|
    // forward = (0, 9, -7)/n; x = forward x up = (1, 0, 0); y = forward x x = (0, -7, -9)/n.
    const glm::dvec3 rows[3] = {{1.0, 0.0, 0.0}, {0.0, -7.0 / n, -9.0 / n}, {0.0, 9.0 / n, -7.0 / n}};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(camera.rotation[c][r], rows[r][c], 1e-15) << r << "," << c;
    EXPECT_NEAR(glm::length(camera.centre() - glm::dvec3(0.0, -9.0, 7.0)), 0.0, 1e-14);
    EXPECT_EQ(camera.cx, 960.0);
    EXPECT_EQ(camera.cy, 540.0);
    EXPECT_NO_THROW(camera.validate());
}

TEST(LookAt, TargetProjectsToTheImageCentre) {
    const Camera camera = benchmark_camera();
    const glm::dvec2 origin = image_point(camera, {0.0, 0.0, 0.0});
    EXPECT_NEAR(origin.x, 960.0, 1e-9);
    EXPECT_NEAR(origin.y, 540.0, 1e-9);
    EXPECT_NEAR(camera.to_camera({0.0, 0.0, 0.0}).z, std::sqrt(130.0), 1e-12);
}

TEST(LookAt, WorldXIsRightAndWorldUpIsUpInThePicture) {
    const Camera camera = benchmark_camera();
    const double n = std::sqrt(130.0);
    // (1, 0, 0) - eye = (1, 9, -7): camera (1, 0, 130/n), so u = 960 + 1400/n.
    const glm::dvec2 right = image_point(camera, {1.0, 0.0, 0.0});
    EXPECT_NEAR(right.x, 960.0 + 1400.0 / n, 1e-9);
    EXPECT_NEAR(right.y, 540.0, 1e-9);
    EXPECT_GT(right.x, 960.0);
    // (0, 0, 1) - eye = (0, 9, -6): camera (0, -9/n, 123/n), so v = 540 - 1400 * 9/123.
    const glm::dvec2 up = image_point(camera, {0.0, 0.0, 1.0});
    EXPECT_NEAR(up.x, 960.0, 1e-9);
    EXPECT_NEAR(up.y, 540.0 - 1400.0 * 9.0 / 123.0, 1e-9);
    EXPECT_LT(up.y, 540.0);
}

TEST(LookAt, RejectsDegenerateViews) {
    EXPECT_THROW(Camera::look_at({1, 2, 3}, {1, 2, 3}, {0, 0, 1}, 10, 10, 10, 10), InputError);
    EXPECT_THROW(Camera::look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 1}, 10, 10, 10, 10), InputError);
    EXPECT_THROW(Camera::look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 0}, 10, 10, 10, 10), InputError);
}

TEST(Resized, ScalesIntrinsicsSoPointsKeepTheirRelativePosition) {
    Camera camera = benchmark_camera();
    camera.cx = 900.0;  // off-centre, to see it scale too
    const Camera half = camera.resized(960, 540);
    EXPECT_EQ(half.width, 960);
    EXPECT_EQ(half.height, 540);
    EXPECT_DOUBLE_EQ(half.fx, 700.0);
    EXPECT_DOUBLE_EQ(half.fy, 700.0);
    EXPECT_DOUBLE_EQ(half.cx, 450.0);
    EXPECT_DOUBLE_EQ(half.cy, 270.0);
    EXPECT_EQ(half.rotation, camera.rotation);
    EXPECT_EQ(half.translation, camera.translation);
    const glm::dvec3 point{0.3, -0.2, 0.9};
    const glm::dvec2 full = image_point(camera, point), small = image_point(half, point);
    EXPECT_NEAR(small.x, full.x / 2.0, 1e-9);
    EXPECT_NEAR(small.y, full.y / 2.0, 1e-9);

    const Camera wide = camera.resized(3840, 1080);  // anisotropic scaling
    EXPECT_DOUBLE_EQ(wide.fx, 2800.0);
    EXPECT_DOUBLE_EQ(wide.fy, 1400.0);
    EXPECT_DOUBLE_EQ(wide.cx, 1800.0);
    EXPECT_DOUBLE_EQ(wide.cy, 540.0);
}

}  // namespace
}  // namespace vksplat
