// GaussianCloud bookkeeping: resize, append, consistency, subset, SH degree changes.
#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

// A cloud whose every value encodes (Gaussian, slot), so copies can be traced.
GaussianCloud numbered_cloud(size_t n, int degree) {
    GaussianCloud cloud;
    cloud.sh_degree = degree;
    cloud.resize(n);
    const auto fill = [](std::vector<float>& values, size_t per) {
        for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>((i / per) * 100 + i % per);
    };
    fill(cloud.positions, 3);
    fill(cloud.log_scales, 3);
    fill(cloud.rotations, 4);
    fill(cloud.opacity_logits, 1);
    fill(cloud.sh, static_cast<size_t>(cloud.sh_coefficients()) * 3);
    return cloud;
}

TEST(GaussianCloud, ResizeSizesEveryArrayForTheDegreeAndZeroesNewEntries) {
    for (int degree = 0; degree <= 3; ++degree) {
        GaussianCloud cloud;
        cloud.sh_degree = degree;
        cloud.resize(5);
        EXPECT_EQ(cloud.size(), 5u);
        EXPECT_EQ(cloud.positions.size(), 15u);
        EXPECT_EQ(cloud.log_scales.size(), 15u);
        EXPECT_EQ(cloud.rotations.size(), 20u);
        EXPECT_EQ(cloud.sh.size(), 5u * 3 * static_cast<size_t>((degree + 1) * (degree + 1)));
        EXPECT_NO_THROW(cloud.check_consistent());
    }
    GaussianCloud cloud = numbered_cloud(2, 1);
    cloud.resize(3);
    EXPECT_EQ(cloud.positions[3], 100.0f);  // old entries kept
    for (int k = 0; k < 3; ++k) EXPECT_EQ(cloud.positions[6 + k], 0.0f);
    EXPECT_EQ(cloud.opacity_logits[2], 0.0f);
    cloud.resize(1);
    EXPECT_EQ(cloud.size(), 1u);
    EXPECT_NO_THROW(cloud.check_consistent());
}

TEST(GaussianCloud, AppendCopiesOneGaussian) {
    const GaussianCloud source = numbered_cloud(3, 2);
    GaussianCloud target;
    target.sh_degree = 2;
    target.append(source, 2);
    target.append(source, 0);
    ASSERT_EQ(target.size(), 2u);
    EXPECT_NO_THROW(target.check_consistent());
    EXPECT_EQ(target.positions[0], 200.0f);
    EXPECT_EQ(target.positions[3], 0.0f);
    EXPECT_EQ(target.rotations[3], 203.0f);
    EXPECT_EQ(target.opacity_logits[0], 200.0f);
    EXPECT_EQ(target.sh[26], 226.0f);  // last SH value of Gaussian 2 (27 per Gaussian)
}

TEST(GaussianCloud, AppendRejectsAnotherDegreeOrAMissingIndex) {
    const GaussianCloud source = numbered_cloud(3, 2);
    GaussianCloud other_degree;
    other_degree.sh_degree = 3;
    EXPECT_THROW(other_degree.append(source, 0), std::invalid_argument);
    GaussianCloud target;
    target.sh_degree = 2;
    EXPECT_THROW(target.append(source, 3), std::out_of_range);
}

TEST(GaussianCloud, CheckConsistentNamesTheArrayThatDisagrees) {
    const GaussianCloud good = numbered_cloud(4, 3);
    EXPECT_NO_THROW(good.check_consistent());
    const auto expect_bad = [](GaussianCloud cloud, const std::string& name) {
        try {
            cloud.check_consistent();
            ADD_FAILURE() << "no error for " << name;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    };
    GaussianCloud bad = good;
    bad.positions.pop_back();
    expect_bad(bad, "positions");
    bad = good;
    bad.log_scales.push_back(0.0f);
    expect_bad(bad, "log_scales");
    bad = good;
    bad.rotations.resize(15);
    expect_bad(bad, "rotations");
    bad = good;
    bad.sh_degree = 2;
    expect_bad(bad, "sh");
    bad = good;
    bad.sh_degree = 4;
    expect_bad(bad, "SH degree 4");
    bad.sh_degree = -1;
    expect_bad(bad, "SH degree -1");
}

TEST(GaussianCloud, SubsetKeepsMarkedGaussiansInOrder) {
    const GaussianCloud cloud = numbered_cloud(5, 1);
    const std::vector<uint8_t> keep{0, 1, 0, 7, 1};
    const GaussianCloud kept = cloud.subset(keep);
    ASSERT_EQ(kept.size(), 3u);
    EXPECT_EQ(kept.sh_degree, 1);
    EXPECT_NO_THROW(kept.check_consistent());
    EXPECT_EQ(kept.opacity_logits, (std::vector<float>{100.0f, 300.0f, 400.0f}));
    EXPECT_EQ(kept.sh[12], 300.0f);  // first SH value of the second kept Gaussian (12 per Gaussian)

    EXPECT_TRUE(cloud.subset(std::vector<uint8_t>(5, 0)).empty());
    EXPECT_THROW(cloud.subset(std::vector<uint8_t>(4, 1)), std::invalid_argument);
}

TEST(GaussianCloud, WithShDegreeTruncatesAndPads) {
    const GaussianCloud cloud = numbered_cloud(2, 3);
    const GaussianCloud degree1 = cloud.with_sh_degree(1);
    EXPECT_EQ(degree1.sh_degree, 1);
    ASSERT_EQ(degree1.sh.size(), 2u * 12);
    for (size_t k = 0; k < 12; ++k) {
        EXPECT_EQ(degree1.sh[k], static_cast<float>(k));
        EXPECT_EQ(degree1.sh[12 + k], static_cast<float>(100 + k));
    }
    EXPECT_EQ(degree1.positions, cloud.positions);
    EXPECT_EQ(degree1.opacity_logits, cloud.opacity_logits);

    const GaussianCloud padded = degree1.with_sh_degree(3);
    ASSERT_EQ(padded.sh.size(), 2u * 48);
    for (size_t k = 0; k < 48; ++k) {
        EXPECT_EQ(padded.sh[k], k < 12 ? static_cast<float>(k) : 0.0f);
        EXPECT_EQ(padded.sh[48 + k], k < 12 ? static_cast<float>(100 + k) : 0.0f);
    }
    EXPECT_EQ(cloud.with_sh_degree(3).sh, cloud.sh);
    EXPECT_THROW(cloud.with_sh_degree(4), std::invalid_argument);
    EXPECT_THROW(cloud.with_sh_degree(-1), std::invalid_argument);
}

}  // namespace
}  // namespace vksplat
