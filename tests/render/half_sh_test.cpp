// SceneStorage::half_sh: half the SH memory, a picture that moves by far less than an 8-bit step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class HalfShTest : public GpuTest {
protected:
    // The cloud rendered with float and with half SH storage, and the device memory each held.
    struct Pair {
        RenderOutput full, half;
        uint64_t full_bytes = 0, half_bytes = 0;
    };
    Pair render_both(const GaussianCloud& cloud, const Camera& camera) {
        Pair pair;
        Renderer full(context()), half(context());
        full.set_scene(cloud);
        half.set_scene(cloud, SceneStorage{.half_sh = true});
        pair.full = full.render(camera);
        pair.full_bytes = full.last_frame().device_bytes;
        pair.half = half.render(camera);
        pair.half_bytes = half.last_frame().device_bytes;
        return pair;
    }
};

TEST_F(HalfShTest, MatchesFloatStorageWithinHalfPrecision) {
    const Pair pair = render_both(random_scene(41, 3000, 3), forward_camera(160, 120, 120.0));
    const RenderOutput &a = pair.full, &b = pair.half;
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    double worst = 0;
    size_t changed = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        ASSERT_TRUE(std::isfinite(b.rgb[i]));
        worst = std::max(worst, double(std::abs(a.rgb[i] - b.rgb[i])));
        changed += a.rgb[i] != b.rgb[i];
    }
    EXPECT_GT(changed, 0u) << "half storage did not change a single value: is it in use?";
    EXPECT_LT(worst, 1.0 / 512) << "more than half an 8-bit step";
    EXPECT_EQ(a.alpha, b.alpha) << "SH only colours; coverage must not move";
    // 48 SH floats per Gaussian at degree 3 become 48 halves.
    EXPECT_EQ(pair.full_bytes - pair.half_bytes, 3000u * 48u * 2u);
}

TEST_F(HalfShTest, OutOfRangeCoefficientsAreClampedNotInfinite) {
    GaussianCloud cloud = random_scene(42, 50, 1);
    for (size_t i = 0; i < cloud.sh.size(); i += 7) cloud.sh[i] = 1e30f;
    Renderer renderer(context());
    renderer.set_scene(cloud, SceneStorage{.half_sh = true});
    const RenderOutput out = renderer.render(forward_camera(64, 64, 60.0));
    for (float v : out.rgb) ASSERT_TRUE(std::isfinite(v));
}

TEST_F(HalfShTest, OddCoefficientCountsAtDegreeZero) {
    // Three halves per Gaussian: every second Gaussian starts in the middle of a word.
    const Pair pair = render_both(random_scene(43, 501, 0), forward_camera(96, 96, 90.0));
    for (size_t i = 0; i < pair.full.rgb.size(); ++i)
        ASSERT_NEAR(pair.full.rgb[i], pair.half.rgb[i], 1.0 / 512) << "value " << i;
}

}  // namespace
}  // namespace vksplat::test
