// reference::project, one Gaussian at a time, against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/scenes.hpp"
#include "vksplat/constants.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/reference/sh.hpp"

namespace vksplat::reference {
namespace {

using namespace vksplat::constants;
using test::add_splat;
using test::at_pixel;
using test::forward_camera;
using test::Splat;

// float log-scales and logits carry ~1e-7 relative error into the expected values.
constexpr double kTol = 1e-5;

ProjectedGaussian project_one(const Splat& splat, const Camera& camera, int degree = 0) {
    GaussianCloud cloud;
    add_splat(cloud, splat);
    return project(cloud, 0, camera, degree);
}

TEST(Project, IsotropicGaussianFacingTheCamera) {
    // 65 x 65 so that the centre of the view lands on pixel (32, 32): u = fx x/z + cx - 0.5.
    const Camera camera = forward_camera(65, 65, 100.0);
    const Splat splat{.position = {0.0, 0.0, 5.0}, .scale = glm::dvec3(0.1), .opacity = 0.5};
    const ProjectedGaussian p = project_one(splat, camera);
    ASSERT_TRUE(p.visible);
    EXPECT_DOUBLE_EQ(p.depth, 5.0);
    EXPECT_NEAR(p.mean.x, 32.0, 1e-12);
    EXPECT_NEAR(p.mean.y, 32.0, 1e-12);
    // sigma^2 f^2 / z^2 = 0.01 * 10000 / 25 = 4, plus the low-pass filter; no correlation.
    const double a = 4.0 + kLowPassFilter;
    EXPECT_NEAR(p.cov2d.x, a, kTol);
    EXPECT_NEAR(p.cov2d.y, 0.0, 1e-12);
    EXPECT_NEAR(p.cov2d.z, a, kTol);
    EXPECT_NEAR(p.conic.x, 1.0 / a, kTol);
    EXPECT_NEAR(p.conic.y, 0.0, 1e-12);
    EXPECT_NEAR(p.conic.z, 1.0 / a, kTol);
    // Equal eigenvalues: mid^2 - det = 0, so the floor applies: lambda = 4.3 + sqrt(0.1) = 4.6162;
    // 3 sqrt(4.6162) = 6.45 -> 7.
    EXPECT_EQ(p.radius, 7);
    // Tiles: (32 - 7) / 16 = 1.56 -> 1; (32 + 7 + 15) / 16 = 3.375 -> 3.
    EXPECT_EQ(p.rect_min, glm::ivec2(1, 1));
    EXPECT_EQ(p.rect_max, glm::ivec2(3, 3));
    EXPECT_NEAR(p.opacity, 0.5, 1e-7);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.color[c], splat.color[c], 1e-6);
}

TEST(Project, NearPlaneCull) {
    const Camera camera = forward_camera(64, 64, 50.0);
    EXPECT_FALSE(project_one({.position = {0.0, 0.0, 0.19}}, camera).visible);
    EXPECT_FALSE(project_one({.position = {0.0, 0.0, kNearPlane}}, camera).visible);  // "z <= near" is culled
    EXPECT_TRUE(project_one({.position = {0.0, 0.0, 0.21}}, camera).visible);
    const ProjectedGaussian behind = project_one({.position = {0.0, 0.0, -5.0}}, camera);
    EXPECT_FALSE(behind.visible);
    EXPECT_DOUBLE_EQ(behind.depth, -5.0);
}

TEST(Project, QuaternionIsWFirstAndNormalised) {
    const Camera camera = forward_camera(64, 64, 100.0);
    const double h = std::numbers::sqrt2 / 2.0;
    // Scales (0.2, 0.1, 0.1) at z = 5: f^2/z^2 = 400, so variances 16 and 4 px^2.
    Splat splat{.position = {0.0, 0.0, 5.0}, .scale = {0.2, 0.1, 0.1}};
    ProjectedGaussian p = project_one(splat, camera);
    EXPECT_NEAR(p.cov2d.x, 16.0 + kLowPassFilter, 1e-4);
    EXPECT_NEAR(p.cov2d.z, 4.0 + kLowPassFilter, 1e-4);
    // 90 degrees about z (w = cos 45, z = sin 45), given unnormalised: the long axis turns to y.
    splat.rotation = glm::dvec4(h, 0.0, 0.0, h) * 3.0;
    p = project_one(splat, camera);
    EXPECT_NEAR(p.cov2d.x, 4.0 + kLowPassFilter, 1e-4);
    EXPECT_NEAR(p.cov2d.y, 0.0, 1e-4);
    EXPECT_NEAR(p.cov2d.z, 16.0 + kLowPassFilter, 1e-4);
    // 45 degrees about z: the long axis along (1, 1); covariance (16 + 4)/2 on the diagonal and
    // (16 - 4)/2 = 6 off it.
    splat.rotation = {std::cos(std::numbers::pi / 8), 0.0, 0.0, std::sin(std::numbers::pi / 8)};
    p = project_one(splat, camera);
    EXPECT_NEAR(p.cov2d.x, 10.0 + kLowPassFilter, 1e-4);
    EXPECT_NEAR(p.cov2d.y, 6.0, 1e-4);
    EXPECT_NEAR(p.cov2d.z, 10.0 + kLowPassFilter, 1e-4);
    const double det = p.cov2d.x * p.cov2d.z - p.cov2d.y * p.cov2d.y;
    EXPECT_NEAR(p.conic.y, -6.0 / det, 1e-6);
    // Distinct eigenvalues 16.3 and 4.3: radius = ceil(3 sqrt(16.3)) = ceil(12.11) = 13.
    EXPECT_EQ(p.radius, 13);
}

TEST(Project, JacobianIsClampedBeyondTheImage) {
    const Camera camera = forward_camera(65, 65, 100.0);
    // x/z = +-10 is far outside the view; the Jacobian is taken at x/z = +-1.3 tan(fov/2).
    const double f2 = 100.0 * 100.0 / 25.0, sigma2 = 0.01;
    for (double side : {1.0, -1.0}) {
        const ProjectedGaussian p = project_one({.position = {side * 50.0, 0.0, 5.0}}, camera);
        const double limit = kJacobianClamp * camera.tan_half_fov_x();
        EXPECT_NEAR(p.cov2d.x, sigma2 * f2 * (1.0 + limit * limit) + kLowPassFilter, kTol);
        EXPECT_NEAR(p.cov2d.y, 0.0, 1e-12);
        EXPECT_NEAR(p.cov2d.z, sigma2 * f2 + kLowPassFilter, kTol);
        EXPECT_FALSE(p.visible);  // and it is off screen
    }
    // Off-centre principal point: each side keeps the 0.3 tan(fov/2) margin past its own edge.
    Camera off = camera;
    off.cx = 10.5;
    off.cy = 60.0;
    const double margin_x = (kJacobianClamp - 1.0) * off.tan_half_fov_x();
    const double margin_y = (kJacobianClamp - 1.0) * off.tan_half_fov_y();
    const struct {
        glm::dvec3 position;
        double limit_x, limit_y;
    } cases[] = {{{50.0, 50.0, 5.0}, (65.0 - 10.5) / 100.0 + margin_x, (65.0 - 60.0) / 100.0 + margin_y},
                 {{-50.0, -50.0, 5.0}, 10.5 / 100.0 + margin_x, 60.0 / 100.0 + margin_y}};
    for (const auto& c : cases) {
        const ProjectedGaussian p = project_one({.position = c.position}, off);
        EXPECT_NEAR(p.cov2d.x, sigma2 * f2 * (1.0 + c.limit_x * c.limit_x) + kLowPassFilter, kTol);
        EXPECT_NEAR(p.cov2d.z, sigma2 * f2 * (1.0 + c.limit_y * c.limit_y) + kLowPassFilter, kTol);
        // Both clamped by the same ratio signs: the correlation is (f/z)^2 sigma^2 tx ty.
        EXPECT_NEAR(p.cov2d.y, sigma2 * f2 * c.limit_x * c.limit_y, kTol);
    }
}

TEST(Project, TileRectangleTruncatesTowardZero) {
    const Camera camera = forward_camera(100, 50, 100.0);  // grid 7 x 4, last row and column partial
    // sigma^2 f^2 / z^2 = 0.5 on the axis, growing to at most 0.72 at the edges with the Jacobian's
    // off-axis term: 3 sqrt(s + 0.3 + sqrt(0.1)) stays in (3, 4), so the radius is 4 in every case.
    const double sigma = std::sqrt(0.5) * 5.0 / 100.0;
    const auto at = [&camera, sigma](double u, double v) {
        const ProjectedGaussian p =
            project_one({.position = at_pixel(camera, u, v, 5.0), .scale = glm::dvec3(sigma)}, camera);
        EXPECT_EQ(p.radius, 4) << u << ", " << v;
        return p;
    };
    ProjectedGaussian p = at(-3.0, 20.0);  // x: (-7)/16 -> 0, (16)/16 -> 1; y: 16/16 -> 1, 39/16 -> 2
    EXPECT_TRUE(p.visible);
    EXPECT_EQ(p.rect_min, glm::ivec2(0, 1));
    EXPECT_EQ(p.rect_max, glm::ivec2(1, 2));
    p = at(-3.5, 20.0);  // (15.5)/16 -> 0: no tile touched, culled
    EXPECT_FALSE(p.visible);
    EXPECT_EQ(p.rect_min.x, 0);
    EXPECT_EQ(p.rect_max.x, 0);
    p = at(105.0, 49.0);  // beyond the right edge, within reach of the last (partial) column
    EXPECT_TRUE(p.visible);
    EXPECT_EQ(p.rect_min, glm::ivec2(6, 2));  // 101/16 -> 6, 45/16 -> 2
    EXPECT_EQ(p.rect_max, glm::ivec2(7, 4));  // 124/16 -> 7, 68/16 -> 4 (clamped to the grid)
    p = at(1e9, 20.0);  // far off: clamped to the grid, no integer overflow
    EXPECT_FALSE(p.visible);
    EXPECT_EQ(p.rect_min.x, 7);
    EXPECT_EQ(p.rect_max.x, 7);
}

TEST(Project, ColourIsShAlongTheViewingRayPlusOffsetClampedAtZero) {
    const Camera camera = forward_camera(64, 64, 10.0);  // wide enough to see both splats
    GaussianCloud cloud;
    cloud.sh_degree = 1;
    add_splat(cloud, {.position = {0.0, 0.0, 5.0}, .color = {0.5, 0.5, 0.5}});  // DC 0
    add_splat(cloud, {.position = {3.0, 0.0, 4.0}, .color = {0.5, 0.5, 0.5}});
    // Band 1, coefficient 2 (the z term, +C1 z) and coefficient 3 (the x term, -C1 x) on red only.
    for (size_t i = 0; i < 2; ++i) {
        cloud.sh[i * 12 + 2 * 3] = 0.4f;
        cloud.sh[i * 12 + 3 * 3] = 3.0f;
    }
    ProjectedGaussian p = project(cloud, 0, camera, 1);  // dir (0, 0, 1)
    EXPECT_NEAR(p.color[0], 0.5 + kShC1 * 0.4, 1e-7);
    EXPECT_NEAR(p.color[1], 0.5, 1e-7);
    p = project(cloud, 1, camera, 1);  // dir (0.6, 0, 0.8): 0.5 + C1 (0.8 * 0.4 - 0.6 * 3) < 0
    ASSERT_TRUE(p.visible);
    EXPECT_EQ(p.color[0], 0.0);
    p = project(cloud, 1, camera, 0);  // degree 0 asked: band 1 ignored
    EXPECT_NEAR(p.color[0], 0.5, 1e-7);
    p = project(cloud, 1, camera, 3);  // more than the cloud has: capped to 1
    EXPECT_EQ(p.color[0], 0.0);
}

TEST(Project, RotatedCameraUsesItsCentreForTheViewDirection) {
    // look_at from (0, -9, 7): a splat at the target is straight ahead, at the image centre.
    const Camera camera = Camera::look_at({0.0, -9.0, 7.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 192, 108, 140.0, 140.0);
    GaussianCloud cloud;
    cloud.sh_degree = 1;
    add_splat(cloud, {.position = {0.0, 0.0, 0.0}, .color = {0.5, 0.5, 0.5}});
    cloud.sh[1 * 3 + 0] = 1.0f;  // -C1 y on red: the view direction is (0, 9, -7)/sqrt(130)
    const ProjectedGaussian p = project(cloud, 0, camera, 1);
    ASSERT_TRUE(p.visible);
    EXPECT_NEAR(p.depth, std::sqrt(130.0), 1e-12);
    EXPECT_NEAR(p.mean.x, 95.5, 1e-9);
    EXPECT_NEAR(p.mean.y, 53.5, 1e-9);
    EXPECT_NEAR(p.color[0], std::max(0.0, 0.5 - kShC1 * 9.0 / std::sqrt(130.0)), 1e-7);
}

}  // namespace
}  // namespace vksplat::reference
