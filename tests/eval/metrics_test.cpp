// PSNR and SSIM against numbers computed independently by scikit-image (reference_values.py).
#include "vksplat/eval/metrics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vksplat::eval {
namespace {

// Numerical Recipes' 32-bit LCG, written identically in reference_values.py.
class Lcg {
public:
    explicit Lcg(uint32_t seed) : state_(seed) {}
    double next() {
        state_ = state_ * 1664525u + 1013904223u;
        return static_cast<double>(state_ >> 8) / 16777216.0;
    }

private:
    uint32_t state_;
};

// A smooth gradient plus noise (variant 0), or a distorted copy of it (variant 1): the same
// double arithmetic, in the same order, as make_test_image() in reference_values.py. Some values
// fall outside [0, 1], so the clamping is exercised too.
std::vector<float> make_test_image(int width, int height, int channels, uint32_t seed, int variant) {
    Lcg noise(seed), distortion(seed + 1);
    std::vector<float> img(static_cast<size_t>(width) * height * channels);
    size_t i = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double u = x / static_cast<double>(width - 1);
            const double v = y / static_cast<double>(height - 1);
            for (int c = 0; c < channels; ++c) {
                double value = 0.5 * u + 0.3 * v * v + 0.1 * c + 0.3 * (noise.next() - 0.5);
                const double d = distortion.next();
                if (variant == 1) value = value + 0.15 * (d - 0.5) + 0.08 * u * v - 0.05;
                img[i++] = static_cast<float>(value);
            }
        }
    return img;
}

constexpr int kSsimRadius = 5;  // the 11-tap window's half-width

struct Reference {
    int width, height, channels;
    uint32_t seed;
    double psnr, ssim;
};

// From `/usr/bin/python3 tests/eval/reference_values.py` (scikit-image 0.19.3, NumPy 1.24.2):
//   psnr = peak_signal_noise_ratio(a, b, data_range=1.0)
//   ssim = structural_similarity(a, b, channel_axis=2 (None for 1 channel), data_range=1.0,
//                                gaussian_weights=True, sigma=1.5, use_sample_covariance=False)
// with a, b = make_test_image(...) clipped to [0, 1] and converted to float64.
constexpr Reference kReferences[] = {
    {37, 29, 3, 12345, 25.372963298298995, 0.89505942707312081},
    {64, 48, 3, 777, 25.21111352510389, 0.88503473668424171},
    {23, 17, 1, 4242, 25.604854863451884, 0.90736542723573055},
    {11, 11, 3, 99, 25.341918152404528, 0.92991652067497299},  // a single valid pixel
};

TEST(Metrics, PsnrMatchesScikitImage) {
    for (const Reference& ref : kReferences) {
        const auto a = make_test_image(ref.width, ref.height, ref.channels, ref.seed, 0);
        const auto b = make_test_image(ref.width, ref.height, ref.channels, ref.seed, 1);
        EXPECT_NEAR(psnr(a.data(), b.data(), ref.width, ref.height, ref.channels), ref.psnr, 1e-6)
            << ref.width << " x " << ref.height << " x " << ref.channels;
    }
}

TEST(Metrics, SsimMatchesScikitImage) {
    for (const Reference& ref : kReferences) {
        const auto a = make_test_image(ref.width, ref.height, ref.channels, ref.seed, 0);
        const auto b = make_test_image(ref.width, ref.height, ref.channels, ref.seed, 1);
        EXPECT_NEAR(ssim(a.data(), b.data(), ref.width, ref.height, ref.channels), ref.ssim, 1e-6)
            << ref.width << " x " << ref.height << " x " << ref.channels;
    }
}

TEST(Metrics, SsimIsSymmetric) {
    const auto a = make_test_image(40, 30, 3, 5, 0);
    const auto b = make_test_image(40, 30, 3, 5, 1);
    EXPECT_NEAR(ssim(a.data(), b.data(), 40, 30), ssim(b.data(), a.data(), 40, 30), 1e-12);
}

TEST(Metrics, IdenticalImagesGivePerfectScores) {
    const auto a = make_test_image(32, 24, 3, 8, 0);
    EXPECT_EQ(psnr(a.data(), a.data(), 32, 24), std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(ssim(a.data(), a.data(), 32, 24), 1.0);
}

TEST(Metrics, ValuesOutsideTheUnitRangeAreClampedFirst) {
    // -0.5 and 0 both save as black, 1 and 7 both as white: no difference at all.
    const std::vector<float> a = {-0.5f, 1.0f, 0.25f};
    const std::vector<float> b = {0.0f, 7.0f, 0.25f};
    EXPECT_EQ(psnr(a.data(), b.data(), 1, 1), std::numeric_limits<double>::infinity());
}

TEST(Metrics, ConstantOffsetGivesClosedFormPsnr) {
    // Values and offset are multiples of 1/256, so every difference is exactly 0.125 in float:
    // MSE = 0.125^2 and PSNR = -20 log10(0.125).
    const int w = 16, h = 12;
    std::vector<float> a(static_cast<size_t>(w) * h * 3), b(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = static_cast<float>(i % 97) / 256.0f + 0.25f;
        b[i] = a[i] + 0.125f;
    }
    EXPECT_NEAR(psnr(a.data(), b.data(), w, h), -20.0 * std::log10(0.125), 1e-9);

    // Near white the offset is clipped: 0.9375 + 0.125 saves as 1, a difference of 0.0625.
    std::fill(a.begin(), a.end(), 0.9375f);
    std::fill(b.begin(), b.end(), 0.9375f + 0.125f);
    EXPECT_NEAR(psnr(a.data(), b.data(), w, h), -20.0 * std::log10(0.0625), 1e-9);
}

TEST(Metrics, AFullMaskGivesTheUnmaskedScores) {
    const Reference& ref = kReferences[1];
    const auto a = make_test_image(ref.width, ref.height, 3, ref.seed, 0);
    const auto b = make_test_image(ref.width, ref.height, 3, ref.seed, 1);
    const std::vector<uint8_t> all(size_t(ref.width) * ref.height, 1);
    EXPECT_NEAR(masked_psnr(a.data(), b.data(), all.data(), ref.width, ref.height), ref.psnr, 1e-6);
    EXPECT_NEAR(masked_ssim(a.data(), b.data(), all.data(), ref.width, ref.height), ref.ssim, 1e-6);
}

TEST(Metrics, AMaskCountsOnlyItsPixels) {
    // The images differ by 0.125 on the left half and agree on the right half.
    const int w = 40, h = 30;
    std::vector<float> a = make_test_image(w, h, 3, 3, 0), b = a;
    std::vector<uint8_t> left(size_t(w) * h, 0), right(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            (x < w / 2 ? left : right)[size_t(y) * w + x] = 1;
            if (x >= w / 2) continue;
            for (int c = 0; c < 3; ++c) {
                float& v = a[(size_t(y) * w + x) * 3 + c];
                v = 0.25f + 0.5f * std::clamp(v, 0.0f, 1.0f);
                b[(size_t(y) * w + x) * 3 + c] = v + 0.125f;
            }
        }
    EXPECT_NEAR(masked_psnr(a.data(), b.data(), left.data(), w, h), -20.0 * std::log10(0.125), 1e-5);
    EXPECT_EQ(masked_psnr(a.data(), b.data(), right.data(), w, h), std::numeric_limits<double>::infinity());
    // SSIM windows reach across the seam, so only right-half pixels 6 or more from it score 1.
    std::vector<uint8_t> far_right(size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = w / 2 + kSsimRadius + 1; x < w; ++x) far_right[size_t(y) * w + x] = 1;
    EXPECT_NEAR(masked_ssim(a.data(), b.data(), far_right.data(), w, h), 1.0, 1e-12);
    EXPECT_LT(masked_ssim(a.data(), b.data(), left.data(), w, h), 0.999);
    const std::vector<uint8_t> none(size_t(w) * h, 0);
    EXPECT_TRUE(std::isnan(masked_psnr(a.data(), b.data(), none.data(), w, h)));
    EXPECT_TRUE(std::isnan(masked_ssim(a.data(), b.data(), none.data(), w, h)));
    EXPECT_THROW(masked_psnr(a.data(), b.data(), nullptr, w, h), std::invalid_argument);
}

TEST(Metrics, RejectsBadSizes) {
    const auto a = make_test_image(12, 12, 3, 1, 0);
    EXPECT_THROW(psnr(a.data(), a.data(), 0, 12), std::invalid_argument);
    EXPECT_THROW(psnr(nullptr, a.data(), 12, 12), std::invalid_argument);
    EXPECT_THROW(ssim(a.data(), a.data(), 10, 12), std::invalid_argument);  // under the window
    EXPECT_THROW(error_map(a.data(), a.data(), 12, -1), std::invalid_argument);
}

}  // namespace
}  // namespace vksplat::eval
