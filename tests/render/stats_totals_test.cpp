// Statistics summed over views (Renderer::render_stats_totals): on the device and on the host,
// the exact sums of the views' own statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class StatsTotals : public GpuTest {};

// In view, culled behind the cameras, 50 large splats touching many tiles, and one NaN position
// (dropped by sanitising, so the totals must be indexed like the input).
GaussianCloud mixed_scene() {
    GaussianCloud cloud = random_scene(61, 600, 2);
    for (const GaussianCloud& extra :
         {random_scene(62, 60, 2, -5.0f, -1.0f), random_scene(63, 50, 2, 2.0f, 3.0f, 0.5f, 1.0f)})
        for (size_t i = 0; i < extra.size(); ++i) cloud.append(extra, i);
    cloud.positions[3 * 7] = std::numeric_limits<float>::quiet_NaN();
    return cloud;
}

// The last view is large, so that its first attempt overflows the tile entries grown for the
// others and is drawn again: the overflowed attempt must add nothing.
std::vector<Camera> views() {
    return {forward_camera(96, 72, 80.0),
            Camera::look_at({2.0, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 64, 80, 60.0, 60.0),
            forward_camera(96, 72, 80.0),  // a view twice counts twice
            forward_camera(320, 320, 260.0)};
}

// The views' statistics one by one, summed exactly: blend weights as the 32.32 integers they are.
GaussianTotals expected_totals(Renderer& renderer, const std::vector<Camera>& cameras, size_t n) {
    GaussianTotals totals;
    totals.resize(n);
    std::vector<uint64_t> fixed(n, 0);
    for (const Camera& camera : cameras) {
        const GaussianStats stats = renderer.render_stats(camera);
        for (size_t i = 0; i < n; ++i) {
            fixed[i] += uint64_t(std::ldexp(stats.blend_weight[i], 32));
            totals.max_weight[i] = std::max(totals.max_weight[i], stats.max_weight[i]);
            totals.pixels[i] += stats.pixels[i];
            if (!stats.visible[i]) continue;
            totals.radius_squared[i] += uint64_t(stats.radius[i]) * uint64_t(stats.radius[i]);
            ++totals.views_visible[i];
        }
        ++totals.views;
    }
    for (size_t i = 0; i < n; ++i) totals.blend_weight[i] = std::ldexp(double(fixed[i]), -32);
    return totals;
}

TEST_F(StatsTotals, OnTheDeviceAreTheExactSumsOfEachView) {
    const GaussianCloud cloud = mixed_scene();
    const std::vector<Camera> cameras = views();
    Renderer renderer(context());
    renderer.set_scene(cloud);
    size_t calls = 0;
    const GaussianTotals totals = renderer.render_stats_totals(cameras, {}, [&](size_t done, size_t total) {
        EXPECT_EQ(done, ++calls);
        EXPECT_EQ(total, cameras.size());
    });
    EXPECT_EQ(calls, cameras.size());
    EXPECT_GT(renderer.last_frame().attempts, 1u) << "the last view must have overflowed once";

    Renderer fresh(context());
    fresh.set_scene(cloud);
    const GaussianTotals expected = expected_totals(fresh, cameras, cloud.size());
    ASSERT_EQ(totals.size(), cloud.size());
    EXPECT_EQ(totals.views, cameras.size());
    EXPECT_EQ(totals.blend_weight, expected.blend_weight);
    EXPECT_EQ(totals.max_weight, expected.max_weight);
    EXPECT_EQ(totals.pixels, expected.pixels);
    EXPECT_EQ(totals.radius_squared, expected.radius_squared);
    EXPECT_EQ(totals.views_visible, expected.views_visible);
    EXPECT_EQ(totals.views_visible[7], 0u) << "the dropped Gaussian";
    EXPECT_EQ(totals.blend_weight[7], 0.0);
    size_t twice = 0, blended = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        twice += totals.views_visible[i] >= 2;
        blended += totals.blend_weight[i] > 0.0;
    }
    EXPECT_GT(twice, 300u);
    EXPECT_GT(blended, 300u);
}

TEST_F(StatsTotals, OnTheHostUnderAMemoryBudgetAreTheSame) {
    const GaussianCloud cloud = mixed_scene();
    const std::vector<Camera> cameras = views();
    Renderer on_device(context());
    on_device.set_scene(cloud);
    const GaussianTotals device = on_device.render_stats_totals(cameras);
    // A budget given keeps a host copy (the frame may need chunks): every view comes back.
    Renderer on_host(context());
    on_host.set_scene(cloud, {.memory_budget = uint64_t(1) << 30});
    const GaussianTotals host = on_host.render_stats_totals(cameras);
    EXPECT_EQ(host.views, device.views);
    EXPECT_EQ(host.max_weight, device.max_weight);
    EXPECT_EQ(host.pixels, device.pixels);
    EXPECT_EQ(host.radius_squared, device.radius_squared);
    EXPECT_EQ(host.views_visible, device.views_visible);
    for (size_t i = 0; i < cloud.size(); ++i)  // summed in double here, in fixed point there
        EXPECT_NEAR(host.blend_weight[i], device.blend_weight[i], 1e-12 * device.blend_weight[i]) << i;
}

}  // namespace
}  // namespace vksplat::test
