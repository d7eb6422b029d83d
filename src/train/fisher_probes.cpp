// Fisher information by random-sign probes through the backward pass (vksplat/train/fisher_probes.hpp).
#include "vksplat/train/fisher_probes.hpp"

#include <stdexcept>
#include <string>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "gpu/transfer.hpp"
#include "render/entry_growth.hpp"
#include "render/frame_layout.hpp"
#include "shaders/train/fisher_accumulate.kernel.hpp"
#include "shaders/train/fisher_probe_signs.kernel.hpp"
#include "train/differentiable_renderer.hpp"
#include "train/trainable_scene.hpp"

namespace vksplat::train {
namespace {

using shader::train::FISHER_FLOATS;

// A 32-bit seed for each probe (splitmix64's finaliser): probes of one run, and runs of
// different seeds, draw unrelated signs.
uint32_t probe_seed(uint32_t seed, uint64_t probe) {
    uint64_t z = (uint64_t(seed) << 32 | 0x5bd1e995u) + probe * 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return uint32_t((z ^ (z >> 31)) >> 32);
}

}  // namespace

std::vector<std::array<double, 36>> estimate_fisher(const gpu::Context& context, const GaussianCloud& cloud,
                                                    const std::vector<Camera>& cameras, const RenderSettings& settings,
                                                    const FisherProbeOptions& options,
                                                    const std::function<void(size_t, size_t)>& progress) {
    if (options.probes_per_view == 0) throw std::invalid_argument("estimate_fisher: probes_per_view must be at least 1");
    GaussianCloud checked = cloud;
    if (sanitize(checked).changed() > 0)
        throw std::invalid_argument("estimate_fisher: the cloud needs sanitising first (see sanitize())");
    for (const Camera& camera : cameras) camera.validate();
    const uint32_t n = static_cast<uint32_t>(cloud.size());
    std::vector<std::array<double, 36>> fisher(n, std::array<double, 36>{});
    if (n == 0 || cameras.empty()) return fisher;

    TrainableScene scene = TrainableScene::upload(context, cloud);
    scene.allocate_gradients(context);
    // Per pixel, so that no timing is needed to choose a form: the probes' cost is small beside a re-fit.
    DifferentiableRenderer renderer(context, GradientSums::device_default, BlendBackward::per_pixel);
    const gpu::Kernel<shader::train::FisherProbeSignsKernel> signs(context);
    const gpu::Kernel<shader::train::FisherAccumulateKernel> accumulate(context);
    const gpu::Buffer sums(context, uint64_t(n) * FISHER_FLOATS * sizeof(float), gpu::MemoryKind::device, "Fisher sums");
    gpu::Buffer pixel_grad;
    uint32_t pixel_capacity = 0;
    gpu::CommandStream stream(context);
    stream.begin();
    stream.fill(sums, 0);
    stream.barrier();
    stream.submit_and_wait();

    for (size_t view = 0; view < cameras.size(); ++view) {
        const Camera& camera = cameras[view];
        const auto [pixels, tiles] = render::image_extent(camera);
        renderer.ensure(n, pixels, tiles);
        if (pixels > pixel_capacity) {
            pixel_grad = gpu::Buffer(context, uint64_t(pixels) * 16, gpu::MemoryKind::device, "Fisher probe signs");
            pixel_capacity = pixels;
        }
        for (uint32_t attempts = 1;; ++attempts) {
            const auto params = render::make_camera_params(camera, settings, n, scene.sh_degree, false,
                                                           renderer.entry_capacity());
            stream.begin();
            renderer.record_forward(stream, scene, params);
            // One forward serves every probe: the backward reads what it saved and changes nothing of it.
            for (uint32_t probe = 0; probe < options.probes_per_view; ++probe) {
                stream.dispatch(signs,
                                {.pixel_grad = pixel_grad.address(),
                                 .pixels = pixels,
                                 .seed = probe_seed(options.seed, uint64_t(view) * options.probes_per_view + probe)},
                                gpu::groups_for(pixels));
                stream.barrier();
                renderer.record_backward(stream, scene, pixel_grad.address(), true);
                // A frame that overflowed its tile entries sets the status: those probes add nothing,
                // and the view runs again below with room.
                stream.dispatch(accumulate,
                                {.grads = scene.grads.address(),
                                 .fisher = sums.address(),
                                 .status = renderer.status_buffer().address(),
                                 .count = n},
                                gpu::groups_for(n));
                stream.barrier();
            }
            renderer.record_readback(stream);
            stream.barrier_before_host_read();
            stream.submit_and_wait();
            const uint32_t needed = renderer.entries_needed();
            if ((renderer.status() & kStepOverflowed) == 0) break;
            render::check_frame_attempts(attempts, "view '" + camera.name + "'");
            renderer.grow_entries(needed);
        }
        if (progress) progress(view + 1, cameras.size());
    }

    // Each probe's G G^T has mean F: the sums over a view's probes, divided by their number.
    const auto floats = gpu::read_buffer<float>(context, sums, size_t(n) * FISHER_FLOATS);
    const double per_probe = 1.0 / double(options.probes_per_view);
    for (uint32_t i = 0; i < n; ++i) {
        const float* upper = &floats[size_t(i) * FISHER_FLOATS];
        for (int r = 0; r < 6; ++r)
            for (int c = r; c < 6; ++c, ++upper) fisher[i][r * 6 + c] = fisher[i][c * 6 + r] = double(*upper) * per_probe;
    }
    return fisher;
}

}  // namespace vksplat::train
