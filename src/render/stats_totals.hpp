#pragma once
// StatsTotals: per-Gaussian blend statistics summed over views on the device
// (shaders/render/stats_totals.h), for Renderer::render_stats_totals.
#include <cstdint>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "render/frame_resources.hpp"
#include "shaders/render/stats_totals.kernel.hpp"
#include "vksplat/render_types.hpp"

namespace vksplat::render {

class StatsTotals {
public:
    // Totals of `count` Gaussians, zeroed by the first record_add's command buffer; `kernel` (the
    // renderer's, built once) adds a view.
    StatsTotals(const gpu::Context& context, const gpu::Kernel<shader::render::StatsTotalsKernel>& kernel,
                uint32_t count);

    // Records the adding of the frame's statistics (FrameResources::stat_*, means_depth) after its
    // blend; it adds nothing when the frame needed more than `entry_capacity` tile entries.
    void record_add(gpu::CommandStream& stream, const FrameResources& frame, uint32_t entry_capacity);
    // Reads the totals back and adds them into `out` (sized for the input cloud), device Gaussian
    // i being input Gaussian kept[i] (i itself where kept is empty).
    void add_to(GaussianTotals& out, const std::vector<uint32_t>& kept) const;

private:
    const gpu::Context& context_;
    uint32_t count_;
    bool zeroed_ = false;
    const gpu::Kernel<shader::render::StatsTotalsKernel>& kernel_;
    gpu::Buffer weight_low_, weight_high_, max_weight_, pixels_, radius_squared_, views_visible_;
};

}  // namespace vksplat::render
