// The per-pixel error map and its colouring.
#include "vksplat/eval/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vksplat::eval {
namespace {

TEST(ErrorMap, IsTheMeanAbsoluteErrorOverChannelsOfClampedValues) {
    // Two pixels of RGB; the second has out-of-range values that clamp to equal ones in red.
    const std::vector<float> a = {0.5f, 0.25f, 0.0f, 2.0f, 0.0f, 1.0f};
    const std::vector<float> b = {0.25f, 0.5f, 0.75f, 1.0f, -1.0f, 0.25f};
    const std::vector<float> err = error_map(a.data(), b.data(), 2, 1);
    ASSERT_EQ(err.size(), 2u);
    EXPECT_FLOAT_EQ(err[0], (0.25f + 0.25f + 0.75f) / 3.0f);
    EXPECT_FLOAT_EQ(err[1], (0.0f + 0.0f + 0.75f) / 3.0f);
}

TEST(ErrorMap, HonoursTheChannelCount) {
    const std::vector<float> a = {0.0f, 1.0f, 0.5f, 0.5f};
    const std::vector<float> b = {1.0f, 1.0f, 0.0f, 0.5f};
    EXPECT_EQ(error_map(a.data(), b.data(), 2, 2, 1), (std::vector<float>{1.0f, 0.0f, 0.5f, 0.0f}));
}

// Relative luminance, enough to check that the ramp gets brighter.
double luminance(const std::vector<uint8_t>& rgb, size_t i) {
    return 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
}

TEST(ColorizeHeat, MapsZeroToDarkAndMaxToBrightThroughAMonotonicRamp) {
    std::vector<float> err;
    for (int i = 0; i <= 64; ++i) err.push_back(0.5f * i / 64.0f);
    std::vector<uint8_t> rgb;
    colorize_heat(err, 0.5f, rgb);
    ASSERT_EQ(rgb.size(), err.size() * 3);
    EXPECT_LT(luminance(rgb, 0), 10.0);              // inferno starts near black
    EXPECT_GT(luminance(rgb, err.size() - 1), 200.0);  // and ends pale yellow
    EXPECT_GT(rgb[3 * (err.size() - 1)], rgb[3 * (err.size() - 1) + 2]);  // R > B: RGB order, not BGR
    for (size_t i = 1; i < err.size(); ++i) EXPECT_GE(luminance(rgb, i), luminance(rgb, i - 1)) << i;
}

TEST(ColorizeHeat, SaturatesAboveTheMaximumAndShowsNanAsTheTop) {
    const std::vector<float> err = {1.0f, 5.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.0f};
    std::vector<uint8_t> rgb;
    colorize_heat(err, 1.0f, rgb);
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_EQ(rgb[3 + ch], rgb[ch]);
        EXPECT_EQ(rgb[6 + ch], rgb[ch]);
        EXPECT_EQ(rgb[9 + ch], rgb[12 + ch]);
    }
}

TEST(ColorizeHeat, HandlesEmptyInputAndRejectsABadMaximum) {
    std::vector<uint8_t> rgb = {1, 2, 3};
    colorize_heat({}, 1.0f, rgb);
    EXPECT_TRUE(rgb.empty());
    EXPECT_THROW(colorize_heat({0.1f}, 0.0f, rgb), std::invalid_argument);
    EXPECT_THROW(colorize_heat({0.1f}, std::numeric_limits<float>::infinity(), rgb),
                 std::invalid_argument);
}

}  // namespace
}  // namespace vksplat::eval
