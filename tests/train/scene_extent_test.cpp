// The robust scene extent training scales its rates by.
#include <gtest/gtest.h>

#include <cmath>

#include "vksplat/error.hpp"
#include "vksplat/train/scene_extent.hpp"

namespace vksplat::test {
namespace {

// `count` cameras on a circle of radius 4 around `target`, looking at it.
std::vector<Camera> ring(int count, glm::dvec3 target) {
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * M_PI * i / count;
        const glm::dvec3 eye = target + glm::dvec3(4.0 * std::sin(angle), 0.5 * std::cos(3.0 * angle), 4.0 * std::cos(angle));
        cameras.push_back(Camera::look_at(eye, target, {0, -1, 0}, 64, 48, 60.0, 50.0));
    }
    return cameras;
}

TEST(SceneExtent, OneFarCameraIsDistrustedAndLeftOut) {
    std::vector<Camera> cameras = ring(12, {1, 2, 3});
    const double radius = train::scene_extent(cameras).radius;
    EXPECT_NEAR(radius, 1.1 * 4.0, 0.1 * 4.0);  // 1.1 x the largest distance from the centres' mean
    cameras.push_back(Camera::look_at({185000, 0, 0}, {1, 2, 3}, {0, -1, 0}, 64, 48, 60.0, 50.0));
    const train::SceneExtent robust = train::scene_extent(cameras);
    EXPECT_EQ(robust.distrusted, (std::vector<size_t>{12}));
    EXPECT_NEAR(robust.radius, radius, 1e-9);
    EXPECT_THROW(train::scene_extent({}), InputError);
}

}  // namespace
}  // namespace vksplat::test
