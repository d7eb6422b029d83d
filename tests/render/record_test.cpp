// Renderer::record: the frame recorded into a caller's command buffer leaves in the caller's
// buffer what render() returns, in every target format; a view denser than the buffers recovers on
// the next frame; bad targets are refused. (examples/embed does the same on an adopted device
// with an image target.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

class RecordTest : public GpuTest {
protected:
    // Records one frame into a command buffer of ours, submits it and waits; returns the target's bytes.
    std::vector<uint8_t> record_frame(Renderer& renderer, const Camera& camera, VkFormat format,
                                      const RenderSettings& settings = {}) {
        const size_t bytes = size_t(camera.width) * camera.height * render_target_pixel_bytes(format);
        gpu::Buffer target(context(), bytes + 64, gpu::MemoryKind::readback, "test target");
        gpu::CommandStream ours(context());
        ours.begin();
        renderer.record(ours.handle(), camera, settings, RenderTarget::to_buffer(target.handle(), format, 64));
        ours.submit_and_wait();
        const auto* at = static_cast<const uint8_t*>(target.mapped()) + 64;
        return {at, at + bytes};
    }
};

uint8_t level(float value) { return uint8_t(std::lround(std::fmin(std::fmax(value, 0.0f), 1.0f) * 255.0f)); }

TEST_F(RecordTest, EveryTargetFormatHoldsWhatRenderReturns) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(41, 300, 2));
    const Camera camera = forward_camera(80, 56, 60.0);
    RenderSettings settings;
    settings.background = {0.2f, 0.4f, 0.6f};
    const RenderOutput expected = renderer.render(camera, settings);

    const auto floats = record_frame(renderer, camera, VK_FORMAT_R32G32B32A32_SFLOAT, settings);
    std::vector<float> got(floats.size() / 4);
    std::memcpy(got.data(), floats.data(), floats.size());
    for (size_t i = 0; i < expected.alpha.size(); ++i) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(got[i * 4 + c], expected.rgb[i * 3 + c]) << "pixel " << i;
        ASSERT_EQ(got[i * 4 + 3], expected.alpha[i]) << "pixel " << i;
    }

    for (const VkFormat format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB}) {
        const bool bgra = format == VK_FORMAT_B8G8R8A8_SRGB;
        const auto packed = record_frame(renderer, camera, format, settings);
        int worst = 0;
        for (size_t i = 0; i < expected.alpha.size(); ++i)
            for (int c = 0; c < 4; ++c) {
                const uint8_t want = level(c < 3 ? expected.rgb[i * 3 + c] : expected.alpha[i]);
                const int at = bgra && c < 3 ? 2 - c : c;
                worst = std::max(worst, std::abs(int(want) - int(packed[i * 4 + at])));
            }
        EXPECT_LE(worst, 1) << "format " << format;  // GLSL may round halves either way
    }
}

TEST_F(RecordTest, ADenserViewIsWholeFromTheNextFrame) {
    // Large splats touch far more tiles than the first frame's entry capacity guess (4 per Gaussian).
    const GaussianCloud scene = random_scene(22, 50, 0, 2.0f, 3.0f, 0.5f, 1.0f);
    const Camera camera = forward_camera(256, 256, 200.0);
    Renderer reference(context());
    reference.set_scene(scene);
    const RenderOutput expected = reference.render(camera);

    Renderer renderer(context());
    renderer.set_scene(scene);
    record_frame(renderer, camera, VK_FORMAT_R32G32B32A32_SFLOAT);
    const auto second = record_frame(renderer, camera, VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_GT(renderer.last_frame().tile_entries, 50u * 4u) << "the first frame should have run short";
    const auto third = record_frame(renderer, camera, VK_FORMAT_R32G32B32A32_SFLOAT);
    std::vector<float> got(third.size() / 4);
    std::memcpy(got.data(), third.data(), third.size());
    for (size_t i = 0; i < expected.alpha.size(); ++i) ASSERT_EQ(got[i * 4 + 3], expected.alpha[i]) << "pixel " << i;
    EXPECT_EQ(second, third);
}

TEST_F(RecordTest, BadTargetsAreRefused) {
    Renderer renderer(context());
    renderer.set_scene(random_scene(43, 10, 0));
    const Camera camera = forward_camera(16, 16, 10.0);
    gpu::Buffer target(context(), 16 * 16 * 16, gpu::MemoryKind::readback, "test target");
    gpu::CommandStream ours(context());
    ours.begin();
    RenderSettings stats;
    stats.gather_stats = true;
    const auto good = RenderTarget::to_buffer(target.handle(), VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_THROW(renderer.record(ours.handle(), camera, stats, good), std::invalid_argument);
    EXPECT_THROW(renderer.record(ours.handle(), camera, {}, RenderTarget::to_buffer(target.handle(), VK_FORMAT_R16G16B16A16_SFLOAT)),
                 std::invalid_argument);
    EXPECT_THROW(renderer.record(ours.handle(), camera, {}, RenderTarget{}), std::invalid_argument);
    ours.submit_and_wait();
}

}  // namespace
}  // namespace vksplat::test
