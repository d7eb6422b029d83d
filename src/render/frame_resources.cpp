#include "render/frame_resources.hpp"

#include <algorithm>
#include <cstring>

#include "render/frame_layout.hpp"

namespace vksplat::render {
namespace {

gpu::Buffer device(const gpu::Context& context, uint64_t bytes, const char* name) {
    return gpu::Buffer(context, bytes, gpu::MemoryKind::device, name);
}

}  // namespace

FrameResources::FrameResources(const gpu::Context& context_) : context(&context_) {
    camera = device(context_, sizeof(CameraParams), "camera");
    counters = device(context_, kCounterCount * sizeof(uint32_t), "frame counters");
    recorded_counters =
        gpu::Buffer(context_, kCounterCount * sizeof(uint32_t), gpu::MemoryKind::readback, "recorded frame counters");
    std::memset(recorded_counters.mapped(), 0, kCounterCount * sizeof(uint32_t));
}

void FrameResources::ensure_gaussians(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= gaussian_capacity) return;
    const auto& c = *context;
    const uint64_t n = count;
    means_depth = device(c, n * 16, "projected means and depths");
    conic_opacity = device(c, n * 16, "conics and opacities");
    colors = device(c, n * 16, "splat colours");
    rects = device(c, n * 8, "tile rectangles");
    tiles_touched = device(c, n * 4, "tiles per splat");
    visible = device(c, n * 4, "visibility flags");
    visible_offsets = device(c, n * 4, "visible offsets");
    depth_keys = device(c, n * 4, "depth keys");
    depth_values = device(c, n * 4, "depth-sorted indices");
    sorted_tile_counts = device(c, n * 4, "depth-ordered tile counts");
    entry_offsets = device(c, n * 4, "tile entry offsets");
    scan_scratch = std::make_unique<gpu::PrefixScan::Scratch>(c, count);
    gaussian_capacity = count;
    if (!sort_scratch || sort_scratch->capacity() < count)
        sort_scratch = std::make_unique<gpu::RadixSort::Scratch>(c, std::max(count, entry_capacity));
}

void FrameResources::ensure_entries(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= entry_capacity) return;
    const auto& c = *context;
    tile_keys = device(c, uint64_t(count) * 4, "tile keys");
    tile_values = device(c, uint64_t(count) * 4, "tile entries");
    entry_capacity = count;
    if (!sort_scratch || sort_scratch->capacity() < count)
        sort_scratch = std::make_unique<gpu::RadixSort::Scratch>(c, std::max(count, gaussian_capacity));
}

void FrameResources::ensure_image(uint32_t pixels, uint32_t tiles) {
    pixels = std::max(pixels, 1u);
    if (pixels > pixel_capacity) {
        const auto& c = *context;
        color_alpha = device(c, uint64_t(pixels) * 16, "colour and alpha image");
        depth = device(c, uint64_t(pixels) * 4, "depth image");
        contributors = device(c, uint64_t(pixels) * 4, "contributor counts");
        readback = gpu::Buffer(c, readback_bytes(pixels), gpu::MemoryKind::readback, "image readback");
        pixel_capacity = pixels;
    }
    if (tiles > tile_capacity) {
        ranges = device(*context, uint64_t(tiles) * 8, "tile ranges");
        tile_capacity = tiles;
    }
}

void FrameResources::ensure_stats(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= stats_capacity) return;
    const auto& c = *context;
    stat_weight = device(c, uint64_t(count) * 8, "blend weight per Gaussian");
    stat_max_weight = device(c, uint64_t(count) * 4, "max weight per Gaussian");
    stat_pixels = device(c, uint64_t(count) * 4, "pixels per Gaussian");
    stat_centre_weight = device(c, uint64_t(count) * 4, "centre-pixel weight per Gaussian");
    stats_readback = gpu::Buffer(c, uint64_t(count) * 36, gpu::MemoryKind::readback, "statistics readback");
    stats_capacity = count;
}

void FrameResources::ensure_packed(uint32_t pixels) {
    pixels = std::max(pixels, 1u);
    if (pixels <= packed_capacity) return;
    packed = device(*context, uint64_t(pixels) * 4, "8-bit image");
    packed_capacity = pixels;
}

bool FrameResources::fits(uint32_t gaussians, uint32_t pixels, uint32_t tiles, uint32_t entries) const {
    return std::max(gaussians, 1u) <= gaussian_capacity && std::max(pixels, 1u) <= pixel_capacity &&
           tiles <= tile_capacity && std::max(entries, 1u) <= entry_capacity;
}

VkDeviceSize FrameResources::readback_bytes(uint32_t pixels) {
    return uint64_t(pixels) * 24 + kCounterCount * sizeof(uint32_t);
}

uint64_t FrameResources::device_bytes() const {
    uint64_t total = 0;
    for (const gpu::Buffer* b : {&camera, &counters, &means_depth, &conic_opacity, &colors, &rects, &tiles_touched,
                                 &visible, &visible_offsets, &depth_keys, &depth_values, &sorted_tile_counts,
                                 &entry_offsets, &tile_keys, &tile_values, &color_alpha, &depth, &contributors,
                                 &ranges, &packed, &stat_weight, &stat_max_weight, &stat_pixels,
                                 &stat_centre_weight})
        total += b->size();
    if (scan_scratch) total += scan_scratch->device_bytes();
    if (sort_scratch) total += sort_scratch->device_bytes();
    return total;
}

}  // namespace vksplat::render
