// Morton order of the Gaussians (train/spatial_order.hpp) on the host, and the trainer's re-ordering
// after densification on lavapipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "train/photographed_views.hpp"
#include "train/spatial_order.hpp"

namespace vksplat::test {
namespace {

TEST(MortonOrder, WalksTheZCurveAndPutsTheNonFiniteLast) {
    // The corners of a unit square in z = 0 listed backwards, a NaN point, and the square's centre
    // line: the Z-curve visits (0,0), (1,0), (0,1), (1,1).
    const float nan = std::nanf("");
    const std::vector<float> points = {1, 1, 0, 0, 1, 0, nan, 0, 0, 1, 0, 0, 0, 0, 0};
    EXPECT_EQ(train::morton_order(points.data(), 5), (std::vector<uint32_t>{4, 3, 1, 0, 2}));
    // Points far apart in input order but close in space end up side by side.
    std::vector<float> cloud;
    for (int i = 0; i < 64; ++i) {
        const float x = float((i * 37) % 64);
        cloud.insert(cloud.end(), {x, 0.5f * x, 0.0f});
    }
    const auto order = train::morton_order(cloud.data(), 64);
    for (size_t k = 1; k < order.size(); ++k) EXPECT_LT(cloud[3 * order[k - 1]], cloud[3 * order[k]]);
    EXPECT_TRUE(train::morton_order(nullptr, 0).empty());
}

class SpatialOrder : public PhotographedViews {
protected:
    SpatialOrder() : PhotographedViews(60) {}
};

// Densifying with the order on gives the same Gaussians as without, re-ordered along the curve.
TEST_F(SpatialOrder, DensifyingReordersTheSameGaussians) {
    // Fixed-point gradient sums: both trainers see the same gradients, so densify alike.
    train::TrainOptions options;
    options.deterministic = true;
    train::TrainOptions ordered = options;
    ordered.spatial_order = true;
    train::Trainer plain(context(), truth, options), sorted(context(), truth, ordered);
    for (int s = 0; s < 3; ++s) {
        plain.step(cameras[size_t(s)], photos.at(size_t(s)));
        sorted.step(cameras[size_t(s)], photos.at(size_t(s)));
    }
    train::DensifyRules rules;
    rules.grad_threshold = 0;
    plain.densify(rules);
    sorted.densify(rules);
    const GaussianCloud a = plain.cloud(), b = sorted.cloud();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(train::morton_order(b.positions.data(), uint32_t(b.size())), [&] {
        std::vector<uint32_t> identity(b.size());
        for (uint32_t i = 0; i < identity.size(); ++i) identity[i] = i;
        return identity;
    }());
    const auto sorted_positions = [](std::vector<float> p) {
        std::vector<std::array<float, 3>> points(p.size() / 3);
        for (size_t i = 0; i < points.size(); ++i) points[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
        std::sort(points.begin(), points.end());
        return points;
    };
    EXPECT_EQ(sorted_positions(a.positions), sorted_positions(b.positions));
    EXPECT_TRUE(sorted.step(cameras[0], photos.at(0)).applied);
}

}  // namespace
}  // namespace vksplat::test
