// Accumulation over views: the sums match the per-view statistics, and the lossless pass it feeds
// leaves the renders of those views bit-identical.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "support/test_data.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/prune/selection.hpp"

namespace vksplat::test {
namespace {

class Accumulate : public GpuTest {};

std::vector<Camera> three_cameras() {
    return {forward_camera(64, 48, 60.0),
            Camera::look_at({1.5, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 48, 48, 50.0, 50.0),
            Camera::look_at({-1.0, 0.5, 1.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 56, 40, 45.0, 45.0)};
}

TEST_F(Accumulate, SumsThePerViewStatistics) {
    const GaussianCloud cloud = random_scene(51, 400, 1);
    const std::vector<Camera> cameras = three_cameras();
    Renderer renderer(context());
    size_t calls = 0;
    const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, {0, 2, 1}, {},
                                                       [&](size_t done, size_t total) {
                                                           EXPECT_EQ(done, ++calls);
                                                           EXPECT_EQ(total, 3u);
                                                       });
    EXPECT_EQ(calls, 3u);
    ASSERT_EQ(totals.size(), cloud.size());
    EXPECT_EQ(totals.views, 3u);

    // The statistics of full renders (pictures and all), summed exactly: the blend weights as the
    // 32.32 fixed-point integers they are, the footprint as opacity * pi * the summed squared radii.
    RenderSettings settings;
    settings.gather_stats = true;
    const std::vector<float> opacity = prune::opacities(cloud);
    prune::ViewTotals expected(cloud.size());
    std::vector<uint64_t> fixed(cloud.size(), 0), radius_squared(cloud.size(), 0);
    for (size_t view : {0, 2, 1}) {
        const GaussianStats stats = renderer.render(cameras[view], settings).stats;
        for (size_t i = 0; i < cloud.size(); ++i) {
            fixed[i] += uint64_t(std::ldexp(stats.blend_weight[i], 32));
            expected.blend_max[i] = std::max(expected.blend_max[i], stats.max_weight[i]);
            expected.pixels[i] += stats.pixels[i];
            if (!stats.visible[i]) continue;
            radius_squared[i] += uint64_t(stats.radius[i]) * uint64_t(stats.radius[i]);
            ++expected.views_visible[i];
        }
    }
    for (size_t i = 0; i < cloud.size(); ++i) {
        expected.blend[i] = std::ldexp(double(fixed[i]), -32);
        expected.footprint[i] = double(opacity[i]) * std::numbers::pi * double(radius_squared[i]);
    }
    size_t seen = 0, blended = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        EXPECT_EQ(totals.blend[i], expected.blend[i]) << i;
        EXPECT_EQ(totals.blend_max[i], expected.blend_max[i]) << i;
        EXPECT_EQ(totals.pixels[i], expected.pixels[i]) << i;
        EXPECT_EQ(totals.views_visible[i], expected.views_visible[i]) << i;
        EXPECT_EQ(totals.footprint[i], expected.footprint[i]) << i;
        seen += totals.views_visible[i] > 1;
        blended += totals.blend[i] > 0.0;
    }
    EXPECT_GT(blended, 100u) << "the views must blend what they see";
    EXPECT_GT(seen, 100u) << "the views must overlap for the sums to mean anything";
}

TEST_F(Accumulate, RefusesAViewThatDoesNotExist) {
    Renderer renderer(context());
    EXPECT_THROW(prune::accumulate(renderer, random_scene(52, 10, 0), three_cameras(), {0, 3}, {}), InputError);
}

TEST_F(Accumulate, LosslessPassKeepsTheRendersOfItsViewsBitIdentical) {
    // Gaussians in view, behind the cameras, far off to the side and tiny faint ones: many are
    // droppable, and none of them may change a pixel.
    GaussianCloud cloud = random_scene(53, 600, 3, 2.0f, 8.0f, 0.005f, 0.3f, 6.0f);
    for (const GaussianCloud& extra : {random_scene(54, 80, 3, -5.0f, -1.0f), random_scene(55, 80, 3, 2.0f, 8.0f, 0.0005f, 0.002f)})
        for (size_t i = 0; i < extra.size(); ++i) cloud.append(extra, i);
    const std::vector<Camera> cameras = three_cameras();
    RenderSettings settings;
    settings.background = {0.2f, 0.4f, 0.9f};

    Renderer renderer(context());
    const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, {0, 1, 2}, settings);
    std::vector<RenderOutput> before;
    for (const Camera& camera : cameras) before.push_back(renderer.render(camera, settings));

    const prune::KeepMask keep = prune::lossless_mask(totals);
    const size_t kept = prune::count_kept(keep);
    ASSERT_LT(kept, cloud.size() - 150) << "the scene must hold droppable Gaussians";
    ASSERT_GT(kept, 100u);
    renderer.set_scene(cloud.subset(keep));
    for (size_t v = 0; v < cameras.size(); ++v) {
        const RenderOutput after = renderer.render(cameras[v], settings);
        EXPECT_EQ(after.rgb, before[v].rgb) << "view " << v;
        EXPECT_EQ(after.alpha, before[v].alpha) << "view " << v;
        EXPECT_EQ(after.depth, before[v].depth) << "view " << v;
    }
}

TEST_F(Accumulate, LosslessPassOnARealSceneKeepsItsViewsBitIdentical) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto dir = shared_data_dir() / "snowmiku";
    const GaussianCloud cloud = io::read_ply(dir / "point_cloud.ply");
    std::vector<Camera> cameras;
    for (const Camera& camera : io::read_cameras(dir / "cameras.json")) cameras.push_back(camera.resized(198, 148));
    cameras.resize(3);  // three test views at a fifth of the size keep this quick on a CPU device

    Renderer renderer(context());
    const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, {0, 1, 2}, {});
    std::vector<RenderOutput> before;
    for (const Camera& camera : cameras) before.push_back(renderer.render(camera));
    const prune::KeepMask keep = prune::lossless_mask(totals);
    EXPECT_LT(prune::count_kept(keep), cloud.size() * 95 / 100) << "some of a real scene is unseen from any one side";
    renderer.set_scene(cloud.subset(keep));
    for (size_t v = 0; v < cameras.size(); ++v) EXPECT_EQ(renderer.render(cameras[v]).rgb, before[v].rgb) << v;
}

}  // namespace
}  // namespace vksplat::test
