// Centrality: where a ring of cameras looks, and the threshold that parts subject from background.
#include <gtest/gtest.h>

#include <cmath>

#include "vksplat/cluster/centrality.hpp"

namespace vksplat::cluster {
namespace {

// 12 cameras on a circle of radius 4 around the origin, looking at it, 90 degrees across.
std::vector<Camera> ring() {
    std::vector<Camera> cameras;
    for (int i = 0; i < 12; ++i) {
        const double a = 2.0 * M_PI * i / 12;
        cameras.push_back(Camera::look_at({4 * std::sin(a), 0, 4 * std::cos(a)}, {0, 0, 0}, {0, -1, 0}, 64, 64, 32.0, 32.0));
    }
    return cameras;
}

TEST(Centrality, IsOneWhereEveryCameraLooksAndFallsAwayFromIt) {
    const std::vector<float> positions = {0, 0, 0,      // the focus: the middle of every picture
                                          0, 1.5, 0,    // above it: off-centre in every picture
                                          8, 0, 0,      // outside the ring: central in few pictures, behind many
                                          0, 50, 0};    // far above: in no picture
    const std::vector<float> c = view_centrality(positions, ring());
    ASSERT_EQ(c.size(), 4u);
    EXPECT_NEAR(c[0], 1.0, 1e-6);
    // 1.5 above at distance 4 projects 1.5 / 4 of the half-height off-centre: 1 - 0.375^2.
    EXPECT_NEAR(c[1], 1.0 - 0.375 * 0.375, 1e-6);
    EXPECT_LT(c[2], 0.5);
    EXPECT_GT(c[2], 0.0);
    EXPECT_EQ(c[3], 0.0f);
    EXPECT_EQ(view_centrality(positions, {}), std::vector<float>(4, 0.0f));
}

}  // namespace
}  // namespace vksplat::cluster
