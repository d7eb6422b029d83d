// The subject region: the automatic ball, its parsing, and which pixels of a render it holds.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.hpp"
#include "vksplat/error.hpp"
#include "vksplat/eval/subject_region.hpp"

namespace vksplat::eval {
namespace {

TEST(SubjectRegion, TheAutomaticBallIsAroundTheCommonFocus) {
    const SubjectBall ball = auto_subject_ball(test::camera_ring(9, {1, 2, 3}, 5.0));
    EXPECT_NEAR(glm::length(ball.centre - glm::dvec3(1, 2, 3)), 0.0, 1e-9);
    EXPECT_NEAR(ball.radius, 0.3 * 5.0, 0.02);  // the cameras' heights vary a little
    std::vector<Camera> forward;
    for (int i = 0; i < 4; ++i) forward.push_back(Camera::look_at({double(i), 0, 0}, {double(i), 0, 9}, {0, -1, 0}, 40, 30, 20, 20));
    EXPECT_THROW(auto_subject_ball(forward), InputError);
}

TEST(SubjectRegion, ParsesABallAndRefusesAnythingElse) {
    const SubjectBall ball = parse_subject_ball("0.5,-1,2e-1,0.25");
    EXPECT_EQ(ball.centre, glm::dvec3(0.5, -1, 0.2));
    EXPECT_EQ(ball.radius, 0.25);
    for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "1,2,3,0", "1,2,3,-1", "a,b,c,d", "1,2,3,nan", "1;2;3;4"})
        EXPECT_THROW(parse_subject_ball(bad), InputError) << bad;
}

TEST(SubjectRegion, HoldsTheOpaquePixelsWhosePointLiesInTheBall) {
    // A wall at depth 4 in front of the camera, a ball of radius 1 around its middle: the pixels
    // within 1 of the middle (in the wall's plane) are subject, unless they are mostly transparent.
    const Camera camera = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 40, 30, 20.0, 20.0);
    RenderOutput render;
    render.width = 40;
    render.height = 30;
    render.alpha.assign(40 * 30, 0.9f);
    render.depth.assign(40 * 30, 4.0f);
    render.alpha[15 * 40 + 20] = 0.4f;  // the middle pixel, mostly transparent
    const std::vector<uint8_t> mask = subject_mask(render, camera, {{0, 0, 4}, 1.0});
    size_t inside = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            const double u = (x + 0.5 - 20) / 20.0 * 4, v = (y + 0.5 - 15) / 20.0 * 4;
            const bool expected = u * u + v * v <= 1.0 && !(x == 20 && y == 15);
            EXPECT_EQ(mask[size_t(y) * 40 + x] != 0, expected) << x << "," << y;
            inside += expected;
        }
    EXPECT_GT(inside, 50u);
    // A render of another size is refused.
    render.width = 20;
    EXPECT_THROW(subject_mask(render, camera, {{0, 0, 4}, 1.0}), InputError);
}

}  // namespace
}  // namespace vksplat::eval
