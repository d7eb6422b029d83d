// The cameras' common focus: where a ring of cameras looks, and none for a forward-facing rig.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.hpp"
#include "vksplat/camera/camera_focus.hpp"

namespace vksplat::test {
namespace {

TEST(CommonFocus, IsWhereTheCamerasLook) {
    const auto focus = common_focus(camera_ring(8, {1, 2, 3}, 4.0));
    ASSERT_TRUE(focus);
    EXPECT_NEAR(glm::length(*focus - glm::dvec3(1, 2, 3)), 0.0, 1e-9);
    // A forward-facing rig (parallel axes) has none.
    std::vector<Camera> parallel;
    for (int i = 0; i < 5; ++i) parallel.push_back(Camera::look_at({double(i), 0, 0}, {double(i), 0, 10}, {0, -1, 0}, 64, 48, 60.0, 50.0));
    EXPECT_FALSE(common_focus(parallel));
}

}  // namespace
}  // namespace vksplat::test
