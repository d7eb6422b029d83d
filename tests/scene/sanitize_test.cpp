// sanitize(): each cause is dropped, clamped or replaced as scene.hpp says, and counted once.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// n well-formed Gaussians of degree 1; Gaussian i sits at x = i so survivors can be identified.
GaussianCloud clean_cloud(size_t n) {
    GaussianCloud cloud;
    cloud.sh_degree = 1;
    cloud.resize(n);
    for (size_t i = 0; i < n; ++i) {
        cloud.positions[i * 3] = static_cast<float>(i);
        cloud.rotations[i * 4] = 1.0f;
        for (int k = 0; k < 3; ++k) cloud.log_scales[i * 3 + k] = -2.0f;
        cloud.opacity_logits[i] = 0.5f;
        cloud.sh[i * 12] = 0.25f;
    }
    return cloud;
}

std::vector<float> x_positions(const GaussianCloud& cloud) {
    std::vector<float> xs;
    for (size_t i = 0; i < cloud.size(); ++i) xs.push_back(cloud.positions[i * 3]);
    return xs;
}

TEST(Sanitize, CleanCloudIsUntouched) {
    GaussianCloud cloud = clean_cloud(4);
    const GaussianCloud before = cloud;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.input_count, 4u);
    EXPECT_EQ(report.changed(), 0u);
    EXPECT_EQ(report.summary(), "clean");
    EXPECT_TRUE(report.kept_indices.empty());
    EXPECT_EQ(cloud.positions, before.positions);
    EXPECT_EQ(cloud.sh, before.sh);
    EXPECT_EQ(cloud.opacity_logits, before.opacity_logits);
}

TEST(Sanitize, DropsNonFinitePositions) {
    GaussianCloud cloud = clean_cloud(4);
    cloud.positions[1 * 3 + 2] = kNaN;
    cloud.positions[3 * 3 + 1] = -kInf;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_nonfinite_position, 2u);
    EXPECT_EQ(report.dropped(), 2u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{0.0f, 2.0f}));
    EXPECT_EQ(report.kept_indices, (std::vector<uint32_t>{0, 2}));
    EXPECT_NO_THROW(cloud.check_consistent());
}

TEST(Sanitize, DropsPositionsBeyondTheFloatSafeRange) {
    GaussianCloud cloud = clean_cloud(3);
    cloud.positions[0 * 3 + 1] = 1e6f;   // far, but fine
    cloud.positions[1 * 3 + 2] = -1e20f; // would overflow once squared in the projection
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_nonfinite_position, 1u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{0.0f, 2.0f}));
}

TEST(Sanitize, ClampsHugeShCoefficients) {
    GaussianCloud cloud = clean_cloud(2);
    cloud.sh[1 * 12 + 4] = 3e30f;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.replaced_nonfinite_sh, 1u);
    EXPECT_EQ(cloud.sh[1 * 12 + 4], kMaxShMagnitude);
    EXPECT_EQ(cloud.sh[0], 0.25f);
}

TEST(Sanitize, DropsNonFiniteRotations) {
    GaussianCloud cloud = clean_cloud(3);
    cloud.rotations[0 * 4 + 3] = kInf;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_nonfinite_rotation, 1u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{1.0f, 2.0f}));
}

TEST(Sanitize, DropsZeroLengthQuaternionsButKeepsSmallValidOnes) {
    GaussianCloud cloud = clean_cloud(4);
    cloud.rotations[0 * 4] = 0.0f;                   // exactly zero
    cloud.rotations[1 * 4] = 1e-13f;                 // below 1e-12: no usable direction
    cloud.rotations[2 * 4] = 0.0f;
    cloud.rotations[2 * 4 + 2] = 1e-6f;              // short but well defined: kept
    cloud.rotations[3 * 4 + 1] = 1e-30f;             // extra tiny component on a unit quaternion: kept
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_zero_rotation, 2u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{2.0f, 3.0f}));
}

TEST(Sanitize, DropsNonFiniteScales) {
    GaussianCloud cloud = clean_cloud(3);
    cloud.log_scales[1 * 3 + 1] = kNaN;
    cloud.log_scales[2 * 3] = kInf;  // infinitely large is as undefined as NaN
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_nonfinite_scale, 2u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{0.0f}));
}

TEST(Sanitize, ClampsLogScalesAndCountsGaussians) {
    GaussianCloud cloud = clean_cloud(3);
    cloud.log_scales[0] = -100.0f;
    cloud.log_scales[1] = 50.0f;  // two components of one Gaussian: counted once
    cloud.log_scales[2 * 3 + 2] = kMaxLogScale;  // on the bound: not clamped
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.clamped_scale, 1u);
    EXPECT_EQ(report.dropped(), 0u);
    EXPECT_EQ(cloud.log_scales[0], kMinLogScale);
    EXPECT_EQ(cloud.log_scales[1], kMaxLogScale);
    EXPECT_EQ(cloud.log_scales[2], -2.0f);
    EXPECT_EQ(cloud.log_scales[2 * 3 + 2], kMaxLogScale);
}

TEST(Sanitize, NanOpacityBecomesTransparentAndInfinitiesAreClamped) {
    GaussianCloud cloud = clean_cloud(5);
    cloud.opacity_logits = {kNaN, kInf, -kInf, 1e20f, kMaxOpacityLogit};
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.replaced_nonfinite_opacity, 4u);
    EXPECT_EQ(cloud.opacity_logits,
              (std::vector<float>{-kMaxOpacityLogit, kMaxOpacityLogit, -kMaxOpacityLogit, kMaxOpacityLogit,
                                  kMaxOpacityLogit}));
    EXPECT_EQ(cloud.size(), 5u);
}

TEST(Sanitize, NonFiniteShValuesBecomeZeroAndGaussiansAreCounted) {
    GaussianCloud cloud = clean_cloud(3);
    cloud.sh[0 * 12 + 1] = kNaN;
    cloud.sh[0 * 12 + 11] = kInf;  // second bad value of the same Gaussian: counted once
    cloud.sh[2 * 12 + 5] = -kInf;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.replaced_nonfinite_sh, 2u);
    EXPECT_EQ(cloud.sh[0], 0.25f);  // finite values of the same Gaussian kept
    EXPECT_EQ(cloud.sh[1], 0.0f);
    EXPECT_EQ(cloud.sh[11], 0.0f);
    EXPECT_EQ(cloud.sh[2 * 12 + 5], 0.0f);
    for (float v : cloud.sh) EXPECT_TRUE(std::isfinite(v));
}

TEST(Sanitize, ADroppedGaussianCountsOnceUnderItsFirstCause) {
    GaussianCloud cloud = clean_cloud(2);
    cloud.positions[0] = kNaN;
    cloud.rotations[0] = kNaN;
    cloud.log_scales[0] = kNaN;
    cloud.opacity_logits[0] = kNaN;
    cloud.sh[0] = kNaN;
    const SanitizeReport report = sanitize(cloud);
    EXPECT_EQ(report.dropped_nonfinite_position, 1u);
    EXPECT_EQ(report.changed(), 1u);
    EXPECT_EQ(x_positions(cloud), (std::vector<float>{1.0f}));
}

TEST(Sanitize, SurvivorsKeepTheirOwnDataAfterCompaction) {
    GaussianCloud cloud = clean_cloud(4);
    cloud.positions[0] = kNaN;
    cloud.opacity_logits[3] = 2.0f;
    cloud.sh[3 * 12 + 7] = 0.75f;
    cloud.rotations[3 * 4 + 2] = 0.5f;
    sanitize(cloud);
    ASSERT_EQ(cloud.size(), 3u);
    EXPECT_NO_THROW(cloud.check_consistent());
    EXPECT_EQ(cloud.opacity_logits[2], 2.0f);
    EXPECT_EQ(cloud.sh[2 * 12 + 7], 0.75f);
    EXPECT_EQ(cloud.rotations[2 * 4 + 2], 0.5f);
}

TEST(Sanitize, SummaryHasOneLinePerCause) {
    GaussianCloud cloud = clean_cloud(4);
    cloud.positions[0] = kNaN;
    cloud.log_scales[3] = 99.0f;
    cloud.sh[2 * 12] = kNaN;
    const std::string summary = sanitize(cloud).summary();
    EXPECT_EQ(summary,
              "1 Gaussians dropped: non-finite position or a coordinate beyond +-1e+15\n"
              "1 Gaussians with log-scales clamped to [-23, 13.8]\n"
              "1 Gaussians with non-finite SH coefficients (set to 0) or beyond +-10000 (clamped)");
}

TEST(Sanitize, RejectsAnInconsistentCloud) {
    GaussianCloud cloud = clean_cloud(2);
    cloud.sh.pop_back();
    EXPECT_THROW(sanitize(cloud), std::runtime_error);
}

}  // namespace
}  // namespace vksplat
