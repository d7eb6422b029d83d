// Per-Gaussian SH degree: which bands go, that they go as zeros, and that zeros cost no pixel.
#include <gtest/gtest.h>

#include <stdexcept>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/prune/sh_reduction.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

// Zeroes Gaussian i's bands above `degree` in place.
void zero_bands_above(GaussianCloud& cloud, size_t i, int degree) {
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t f = size_t(sh_coefficients_for_degree(degree)) * 3; f < stride; ++f) cloud.sh[i * stride + f] = 0.0f;
}

TEST(ShReduction, DegreesInUseAreTheHighestNonZeroBand) {
    GaussianCloud cloud = random_scene(81, 4, 3);
    zero_bands_above(cloud, 1, 2);
    zero_bands_above(cloud, 2, 0);
    zero_bands_above(cloud, 3, 1);
    cloud.sh[3 * 48 + 4 * 3 + 2] = 0.5f;  // band 2's first coefficient, blue: in use again
    EXPECT_EQ(prune::sh_degrees_in_use(cloud), (std::vector<uint8_t>{3, 2, 0, 2}));
    EXPECT_EQ(prune::sh_degrees_in_use(random_scene(81, 3, 0)), (std::vector<uint8_t>{0, 0, 0}));
}

TEST(ShReduction, TheCheapestBandsGoFirstAndOnlyWithTheBandsAboveThem) {
    GaussianCloud cloud = random_scene(82, 6, 3);
    // Gaussian 0 is heavy, 5 weightless; 2 has no band 3 to lose and 4 no view-dependent colour.
    zero_bands_above(cloud, 2, 2);
    zero_bands_above(cloud, 4, 0);
    const std::vector<double> weights = {1000, 1, 1, 1, 1, 0};
    // 18 bands: 4 and 5 lose all six cost-free, then 2 its (empty) band 3.
    EXPECT_EQ(prune::reduced_sh_degrees(cloud, weights, 7.0 / 18), (std::vector<uint8_t>{3, 3, 2, 3, 0, 0}));
    for (int bands = 0; bands <= 18; ++bands) {
        const auto degrees = prune::reduced_sh_degrees(cloud, weights, bands / 18.0);
        int dropped = 0;
        for (uint8_t d : degrees) dropped += 3 - d;
        EXPECT_EQ(dropped, bands);
        if (bands < 15) {
            EXPECT_EQ(degrees[0], 3) << "the heavy Gaussian goes last, at " << bands;
        }
    }
    EXPECT_EQ(prune::reduced_sh_degrees(cloud, weights, 0.0), std::vector<uint8_t>(6, 3));
    EXPECT_EQ(prune::reduced_sh_degrees(cloud, weights, 1.0), std::vector<uint8_t>(6, 0));
    // Unweighted, only the energy counts: 5 (full bands) is no longer free.
    EXPECT_EQ(prune::reduced_sh_degrees(cloud, {}, 4.0 / 18), (std::vector<uint8_t>{3, 3, 2, 3, 0, 3}));
    EXPECT_THROW(prune::reduced_sh_degrees(cloud, weights, 1.5), std::invalid_argument);
    EXPECT_THROW(prune::reduced_sh_degrees(cloud, weights, -0.1), std::invalid_argument);
    EXPECT_THROW(prune::reduced_sh_degrees(cloud, std::vector<double>(5, 1.0), 0.5), std::invalid_argument);
}

TEST(ShReduction, ZerosTheBandsAboveEachDegreeAndLowersTheCloudsDegreeWhenAllDo) {
    const GaussianCloud cloud = random_scene(83, 3, 3);
    const GaussianCloud mixed = prune::with_sh_degrees(cloud, std::vector<uint8_t>{3, 1, 0});
    EXPECT_EQ(mixed.sh_degree, 3);
    EXPECT_EQ(prune::sh_degrees_in_use(mixed), (std::vector<uint8_t>{3, 1, 0}));
    EXPECT_EQ(std::vector<float>(mixed.sh.begin(), mixed.sh.begin() + 48),
              std::vector<float>(cloud.sh.begin(), cloud.sh.begin() + 48));
    EXPECT_EQ(std::vector<float>(mixed.sh.begin() + 48, mixed.sh.begin() + 60),
              std::vector<float>(cloud.sh.begin() + 48, cloud.sh.begin() + 60));
    EXPECT_EQ(mixed.positions, cloud.positions);

    const GaussianCloud low = prune::with_sh_degrees(cloud, std::vector<uint8_t>{1, 1, 0});
    EXPECT_EQ(low.sh_degree, 1);
    EXPECT_EQ(low.sh, prune::with_sh_degrees(cloud.with_sh_degree(1), std::vector<uint8_t>{1, 1, 0}).sh);
    EXPECT_THROW(prune::with_sh_degrees(cloud, std::vector<uint8_t>{1, 1}), std::invalid_argument);
}

class ShReductionRender : public GpuTest {};

TEST_F(ShReductionRender, ChangesNoPixelWhereTheRemovedBandsAreZero) {
    GaussianCloud cloud = random_scene(84, 300, 3);
    // A third of the Gaussians lack bands 2 and 3, another third all three: 500 of the 900 bands
    // cost nothing to drop, and are the first to go.
    for (size_t i = 0; i < cloud.size(); i += 3) zero_bands_above(cloud, i, 1);
    for (size_t i = 1; i < cloud.size(); i += 3) zero_bands_above(cloud, i, 0);
    const std::vector<Camera> cameras = {forward_camera(64, 48, 60.0),
                                         Camera::look_at({1.0, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 48, 48, 50.0, 50.0)};
    Renderer renderer(context());
    renderer.set_scene(cloud);
    std::vector<std::vector<float>> before;
    for (const Camera& camera : cameras) before.push_back(renderer.render(camera).rgb);

    const auto render_changes = [&](double share) {
        renderer.set_scene(prune::with_sh_degrees(cloud, prune::reduced_sh_degrees(cloud, {}, share)));
        bool changed = false;
        for (size_t v = 0; v < cameras.size(); ++v) changed |= renderer.render(cameras[v]).rgb != before[v];
        return changed;
    };
    EXPECT_FALSE(render_changes(500.0 / 900));
    EXPECT_TRUE(render_changes(600.0 / 900)) << "bands that are not zero: the test can see a change";

    // Every Gaussian at degree 0 in name only: the cloud becomes degree 0 and still looks the same.
    GaussianCloud flat = random_scene(85, 200, 0).with_sh_degree(3);
    renderer.set_scene(flat);
    before.clear();
    for (const Camera& camera : cameras) before.push_back(renderer.render(camera).rgb);
    const GaussianCloud reduced = prune::with_sh_degrees(flat, prune::reduced_sh_degrees(flat, {}, 1.0));
    EXPECT_EQ(reduced.sh_degree, 0);
    renderer.set_scene(reduced);
    for (size_t v = 0; v < cameras.size(); ++v) EXPECT_EQ(renderer.render(cameras[v]).rgb, before[v]) << v;
}

}  // namespace
}  // namespace vksplat::test
