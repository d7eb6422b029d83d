// The robust scene extent training scales its rates by.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/train/scene_extent.hpp"

namespace vksplat::test {
namespace {

TEST(SceneExtent, OneFarCameraIsDistrustedAndLeftOut) {
    std::vector<Camera> cameras = camera_ring(12, {1, 2, 3}, 4.0);
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
