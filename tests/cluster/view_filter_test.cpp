// The built-in segmentation and the view filter on pictures whose parts are known.
#include <gtest/gtest.h>

#include <random>

#include "vksplat/cluster/segmentation.hpp"
#include "vksplat/cluster/view_filter.hpp"

namespace vksplat::cluster {
namespace {

constexpr int W = 96, H = 64;

// A subject on black: a red disc and a blue square side by side, with a little texture so that
// the picture is not flat; alpha 1 on the subject, 0 elsewhere.
struct Picture {
    std::vector<float> rgb = std::vector<float>(W * H * 3, 0.0f);
    std::vector<float> alpha = std::vector<float>(W * H, 0.0f);
    RegionMap parts{W, H, std::vector<int32_t>(W * H, kNoRegion)};  // the true parts
};

Picture two_parts() {
    Picture p;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> texture(-0.03f, 0.03f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + x;
            int part = -1;
            if ((x - 28) * (x - 28) + (y - 32) * (y - 32) < 18 * 18) part = 0;
            if (x >= 44 && x < 76 && y >= 16 && y < 48) part = 1;  // touches the disc
            if (part < 0) continue;
            p.alpha[i] = 1.0f;
            p.parts.labels[i] = part;
            const float base[2][3] = {{0.8f, 0.15f, 0.1f}, {0.1f, 0.2f, 0.85f}};
            for (int c = 0; c < 3; ++c) p.rgb[i * 3 + c] = base[part][c] + texture(random);
        }
    return p;
}

TEST(Segmentation, FindsThePartsAndLeavesTheBackgroundOut) {
    const Picture p = two_parts();
    const RegionMap map = segment_render(p.rgb, p.alpha, W, H, {.min_size_fraction = 0.01});
    EXPECT_EQ(map.region_count(), 2u);

    // The background carries no region; the subject does, but for slivers along its outline
    // (where smoothing blends it with the background), each pixel in its own part's region.
    size_t agree = 0, labelled = 0;
    for (size_t i = 0; i < map.labels.size(); ++i) {
        if (p.parts.labels[i] == kNoRegion) {
            EXPECT_EQ(map.labels[i], kNoRegion) << i;
            continue;
        }
        ++labelled;
        agree += map.labels[i] == p.parts.labels[i];  // ids compacted in order of first appearance
    }
    EXPECT_GT(double(agree), 0.85 * double(labelled));
}

TEST(ViewFilter, KeepsAMapWhosePartsFollowThePicture) {
    const Picture p = two_parts();
    const ViewQuality q = assess_view(p.parts, p.rgb);
    EXPECT_TRUE(q.keep) << q.reason;
    EXPECT_EQ(q.regions, 2u);
    EXPECT_GT(q.edge_alignment, 1.5);
}

TEST(ViewFilter, DropsOneRegionCoveringEverything) {
    Picture p = two_parts();
    for (auto& id : p.parts.labels)
        if (id >= 0) id = 0;
    const ViewQuality q = assess_view(p.parts, p.rgb);
    EXPECT_FALSE(q.keep);
    EXPECT_NE(q.reason.find("one region covers 100.0%"), std::string::npos) << q.reason;
}

TEST(ViewFilter, DropsANoSubjectView) {
    const RegionMap empty{W, H, std::vector<int32_t>(W * H, kNoRegion)};
    const ViewQuality q = assess_view(empty, std::vector<float>(W * H * 3, 0.0f));
    EXPECT_FALSE(q.keep);
    EXPECT_NE(q.reason.find("no subject"), std::string::npos) << q.reason;
}

TEST(ViewFilter, DropsNoise) {
    const Picture p = two_parts();
    std::mt19937 random(9);
    RegionMap noise = p.parts;
    for (auto& id : noise.labels)
        if (id >= 0) id = int32_t(random() % 8);  // few labels, scattered: borders everywhere
    const ViewQuality few = assess_view(noise, p.rgb);
    EXPECT_FALSE(few.keep);
    EXPECT_NE(few.reason.find("ignore the picture's edges"), std::string::npos) << few.reason;
    for (auto& id : noise.labels)
        if (id >= 0) id = int32_t(random() % 5000);  // thousands of tiny regions
    const ViewQuality many = assess_view(noise, p.rgb);
    EXPECT_FALSE(many.keep);
    EXPECT_NE(many.reason.find("regions (maximum 1000)"), std::string::npos) << many.reason;
}

TEST(ViewFilter, RefusesMismatchedSizes) {
    const Picture p = two_parts();
    EXPECT_THROW(assess_view(p.parts, std::vector<float>(3)), std::invalid_argument);
}

}  // namespace
}  // namespace vksplat::cluster
