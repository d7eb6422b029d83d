// The GPU projection: region id at each Gaussian's centre, and both occlusion rules on scenes
// where what hides what is known.
#include <gtest/gtest.h>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/cluster/projection.hpp"
#include "vksplat/error.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

using cluster::kNoRegion;

class Projection : public GpuTest {
protected:
    const Camera camera = forward_camera(64, 48, 50.0);
    // Left half region 0, right half region 1.
    cluster::RegionMap halves() const {
        cluster::RegionMap map{64, 48, std::vector<int32_t>(64 * 48)};
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) map.labels[size_t(y) * 64 + x] = x < 32 ? 0 : 1;
        return map;
    }
    std::vector<int32_t> project(const GaussianCloud& cloud, const cluster::ProjectionParams& params,
                                 GaussianStats* stats_out = nullptr) {
        Renderer renderer(context());
        renderer.set_scene(cloud);
        RenderSettings settings;
        settings.gather_stats = true;
        const GaussianStats stats = renderer.render(camera, settings).stats;
        if (stats_out) *stats_out = stats;
        cluster::Projector projector(context());
        return projector.project(stats, halves(), params);
    }
    static Splat small(glm::dvec3 position, double opacity = 0.9) {
        return {.position = position, .scale = {0.005, 0.005, 0.005}, .opacity = opacity};
    }
};

TEST_F(Projection, DepthRuleHidesWhatLiesBehindTheNearestCentre) {
    GaussianCloud cloud;
    add_splat(cloud, small(at_pixel(camera, 10, 10, 2.0)));   // nearest in its pixel
    add_splat(cloud, small(at_pixel(camera, 10, 10, 2.14)));  // within 0.05 * 2 + 0.05 = 0.15 behind
    add_splat(cloud, small(at_pixel(camera, 10, 10, 2.2)));   // beyond it: occluded
    add_splat(cloud, small(at_pixel(camera, 40, 30, 5.0)));   // alone, right half
    add_splat(cloud, small({30.0, 0.0, 2.0}));                // outside the image
    add_splat(cloud, small({0.0, 0.0, -2.0}));                // behind the camera
    const auto ids = project(cloud, {});
    EXPECT_EQ(ids, (std::vector<int32_t>{0, 0, kNoRegion, 1, kNoRegion, kNoRegion}));
    // Another tolerance moves the cut.
    const auto strict = project(cloud, {.depth_ratio = 0.0f, .depth_offset = 0.1f});
    EXPECT_EQ(strict, (std::vector<int32_t>{0, kNoRegion, kNoRegion, 1, kNoRegion, kNoRegion}));
}

TEST_F(Projection, BlendRuleSeesWhatThePictureShows) {
    GaussianCloud cloud;
    // Two wide, nearly opaque discs centred on pixel (16, 16): almost nothing shows through them
    // within a few pixels of it.
    add_splat(cloud, {.position = at_pixel(camera, 16, 16, 2.0), .scale = {0.6, 0.6, 0.01}, .opacity = 0.99});
    add_splat(cloud, {.position = at_pixel(camera, 16, 16, 2.05), .scale = {0.6, 0.6, 0.01}, .opacity = 0.99});
    add_splat(cloud, small(at_pixel(camera, 19, 18, 4.0)));  // behind the discs, but alone in its pixel
    add_splat(cloud, small(at_pixel(camera, 50, 40, 4.0)));  // in the open
    GaussianStats stats;
    const auto blend = project(cloud, {.rule = cluster::OcclusionRule::blend}, &stats);
    EXPECT_EQ(blend, (std::vector<int32_t>{0, kNoRegion, kNoRegion, 1}));
    // The centre weight is alpha * T at the centre pixel: nearly the open splat's opacity (its
    // centre is a fraction of a pixel off the pixel's centre), nearly nothing behind the discs.
    EXPECT_GT(stats.centre_weight[3], 0.8f);
    EXPECT_LE(stats.centre_weight[3], 0.9f);
    EXPECT_NEAR(stats.centre_weight[0], 0.99, 1e-3);
    EXPECT_LT(stats.centre_weight[2], 0.005f);
    // The depth rule finds no nearer centre in the hidden splat's pixel, so it counts it as seen.
    const auto depth = project(cloud, {});
    EXPECT_EQ(depth, (std::vector<int32_t>{0, 0, 0, 1}));
}

TEST_F(Projection, EmptySceneAndBadMaps) {
    cluster::Projector projector(context());
    EXPECT_TRUE(projector.project(GaussianStats{}, halves(), {}).empty());
    GaussianStats one;
    one.resize(1);
    EXPECT_THROW(projector.project(one, cluster::RegionMap{}, {}), InputError);
}

}  // namespace
}  // namespace vksplat::test
