#include "render/stats_totals.hpp"

#include <algorithm>

namespace vksplat::render {

StatsTotals::StatsTotals(const gpu::Context& context, const gpu::Kernel<shader::render::StatsTotalsKernel>& kernel,
                         uint32_t count)
    : context_(context), count_(std::max(count, 1u)), kernel_(kernel) {
    const uint64_t n = count_;
    const auto buffer = [&](uint64_t bytes, const char* name) {
        return gpu::Buffer(context, n * bytes, gpu::MemoryKind::device, name);
    };
    weight_low_ = buffer(8, "blend weight totals (low 64 bits)");
    weight_high_ = buffer(4, "blend weight totals (high 32 bits)");
    max_weight_ = buffer(4, "max weight totals");
    pixels_ = buffer(8, "pixel totals");
    radius_squared_ = buffer(8, "squared radius totals");
    views_visible_ = buffer(4, "visible view totals");
}

void StatsTotals::record_add(gpu::CommandStream& stream, const FrameResources& frame, uint32_t entry_capacity) {
    if (!zeroed_) {
        for (const gpu::Buffer* b :
             {&weight_low_, &weight_high_, &max_weight_, &pixels_, &radius_squared_, &views_visible_})
            stream.fill(*b, 0);
        stream.barrier();
        zeroed_ = true;
    }
    const shader::render::StatsTotalsPush push{
        .view = {.means_depth = frame.means_depth.address(),
                 .stat_weight = frame.stat_weight.address(),
                 .stat_max_weight = frame.stat_max_weight.address(),
                 .stat_pixels = frame.stat_pixels.address(),
                 .counters = frame.counters.address()},
        .sums = {.weight_low = weight_low_.address(),
                 .weight_high = weight_high_.address(),
                 .max_weight = max_weight_.address(),
                 .pixels = pixels_.address(),
                 .radius_squared = radius_squared_.address(),
                 .views_visible = views_visible_.address()},
        .count = count_,
        .entry_capacity = entry_capacity};
    stream.dispatch(kernel_, push, gpu::groups_for(count_));
    stream.barrier();
    stream.mark("stats totals");
}

void StatsTotals::add_to(GaussianTotals& out, const std::vector<uint32_t>& kept) const {
    if (!zeroed_) return;  // no view was added
    const uint64_t n = count_;
    gpu::Buffer readback(context_, n * 36, gpu::MemoryKind::readback, "statistics totals readback");
    gpu::CommandStream stream(context_);
    stream.begin();
    stream.copy(weight_low_, readback, n * 8, 0, 0);
    stream.copy(pixels_, readback, n * 8, 0, n * 8);
    stream.copy(radius_squared_, readback, n * 8, 0, n * 16);
    stream.copy(weight_high_, readback, n * 4, 0, n * 24);
    stream.copy(max_weight_, readback, n * 4, 0, n * 28);
    stream.copy(views_visible_, readback, n * 4, 0, n * 32);
    stream.submit_and_wait();

    const auto* base = static_cast<const char*>(readback.mapped());
    const auto* weight_low = reinterpret_cast<const uint64_t*>(base);
    const auto* pixels = reinterpret_cast<const uint64_t*>(base + n * 8);
    const auto* radius_squared = reinterpret_cast<const uint64_t*>(base + n * 16);
    const auto* weight_high = reinterpret_cast<const uint32_t*>(base + n * 24);
    const auto* max_weight = reinterpret_cast<const float*>(base + n * 28);
    const auto* views_visible = reinterpret_cast<const uint32_t*>(base + n * 32);
    for (size_t i = 0; i < std::min<size_t>(n, kept.empty() ? out.size() : kept.size()); ++i) {
        const size_t at = kept.empty() ? i : kept[i];
        // 32.32 fixed point with 32 more bits on top: high * 2^32 + low / 2^32.
        out.blend_weight[at] += double(weight_high[i]) * 4294967296.0 + double(weight_low[i]) / 4294967296.0;
        out.max_weight[at] = std::max(out.max_weight[at], max_weight[i]);
        out.pixels[at] += pixels[i];
        out.radius_squared[at] += radius_squared[i];
        out.views_visible[at] += views_visible[i];
    }
}

}  // namespace vksplat::render
