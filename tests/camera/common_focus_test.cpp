// The cameras' common focus: where a ring of cameras looks, and none for a forward-facing rig.
#include <gtest/gtest.h>

#include <cmath>

#include "vksplat/camera_focus.hpp"

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

TEST(CommonFocus, IsWhereTheCamerasLook) {
    const auto focus = common_focus(ring(8, {1, 2, 3}));
    ASSERT_TRUE(focus);
    EXPECT_NEAR(glm::length(*focus - glm::dvec3(1, 2, 3)), 0.0, 1e-9);
    // A forward-facing rig (parallel axes) has none.
    std::vector<Camera> parallel;
    for (int i = 0; i < 5; ++i) parallel.push_back(Camera::look_at({double(i), 0, 0}, {double(i), 0, 10}, {0, -1, 0}, 64, 48, 60.0, 50.0));
    EXPECT_FALSE(common_focus(parallel));
}

}  // namespace
}  // namespace vksplat::test
