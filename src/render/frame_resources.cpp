#include "render/frame_resources.hpp"

#include <algorithm>
#include <cstring>

#include "render/frame_layout.hpp"

namespace vksplat::render {
namespace {

// A device buffer of `bytes` in place of `buffer`, the old one freed first (gpu::replace), so that
// device memory stays within what bytes_for() promises for the new sizes.
void replace(gpu::Buffer& buffer, const gpu::Context& context, uint64_t bytes, const char* name) {
    gpu::replace(buffer, context, bytes, gpu::MemoryKind::device, name);
}

void replace_sort_scratch(std::unique_ptr<gpu::RadixSort::Scratch>& scratch, const gpu::Context& context,
                          uint32_t count) {
    scratch.reset();
    scratch = std::make_unique<gpu::RadixSort::Scratch>(context, count);
}

}  // namespace

FrameResources::FrameResources(const gpu::Context& context_) : context(&context_) {
    replace(camera, context_, sizeof(CameraParams), "camera");
    replace(counters, context_, kCounterCount * sizeof(uint32_t), "frame counters");
    recorded_counters =
        gpu::Buffer(context_, kCounterCount * sizeof(uint32_t), gpu::MemoryKind::readback, "recorded frame counters");
    std::memset(recorded_counters.mapped(), 0, kCounterCount * sizeof(uint32_t));
}

void FrameResources::ensure_gaussians(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= gaussian_capacity) return;
    const auto& c = *context;
    const uint64_t n = count;
    replace(means_depth, c, n * 16, "projected means and depths");
    replace(footprints, c, n * 32, "splat footprints");
    replace(colors, c, n * 16, "splat colours and depths");
    replace(tiles_touched, c, n * 4, "tiles per splat");
    replace(depth_keys, c, n * 4, "depth keys");
    replace(depth_values, c, n * 4, "depth-sorted indices");
    replace(entry_offsets, c, n * 4, "tile entry offsets");
    scan_scratch.reset();
    scan_scratch = std::make_unique<gpu::PrefixScan::Scratch>(c, count);
    gaussian_capacity = count;
    if (!sort_scratch || sort_scratch->capacity() < count)
        replace_sort_scratch(sort_scratch, c, std::max(count, entry_capacity));
}

void FrameResources::release() {
    for (gpu::Buffer* buffer :
         {&means_depth, &footprints, &colors, &tiles_touched, &depth_keys, &depth_values, &entry_offsets, &tile_keys,
          &tile_values, &color_alpha, &depth, &contributors, &readback, &ranges})
        *buffer = gpu::Buffer();
    scan_scratch.reset();
    sort_scratch.reset();
    gaussian_capacity = entry_capacity = pixel_capacity = tile_capacity = readback_capacity = 0;
}

void FrameResources::ensure_entries(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= entry_capacity) return;
    const auto& c = *context;
    replace(tile_keys, c, uint64_t(count) * 4, "tile keys");
    replace(tile_values, c, uint64_t(count) * 4, "tile entries");
    entry_capacity = count;
    if (!sort_scratch || sort_scratch->capacity() < count)
        replace_sort_scratch(sort_scratch, c, std::max(count, gaussian_capacity));
}

void FrameResources::ensure_image(uint32_t pixels, uint32_t tiles) {
    pixels = std::max(pixels, 1u);
    if (pixels > pixel_capacity) {
        const auto& c = *context;
        replace(color_alpha, c, uint64_t(pixels) * 16, "colour and alpha image");
        replace(depth, c, uint64_t(pixels) * 4, "depth image");
        replace(contributors, c, uint64_t(pixels) * 4, "contributor counts");
        pixel_capacity = pixels;
    }
    if (tiles > tile_capacity) {
        replace(ranges, *context, uint64_t(tiles) * 8, "tile ranges");
        tile_capacity = tiles;
    }
}

void FrameResources::ensure_readback(uint32_t pixels) {
    pixels = std::max(pixels, 1u);
    if (pixels <= readback_capacity) return;
    gpu::replace(readback, *context, readback_bytes(pixels), gpu::MemoryKind::readback, "image readback");
    readback_capacity = pixels;
}

void FrameResources::ensure_stats(uint32_t count) {
    count = std::max(count, 1u);
    if (count <= stats_capacity) return;
    const auto& c = *context;
    replace(stat_weight, c, uint64_t(count) * 8, "blend weight per Gaussian");
    replace(stat_max_weight, c, uint64_t(count) * 4, "max weight per Gaussian");
    replace(stat_pixels, c, uint64_t(count) * 4, "pixels per Gaussian");
    replace(stat_centre_weight, c, uint64_t(count) * 4, "centre-pixel weight per Gaussian");
    stats_readback = gpu::Buffer(c, uint64_t(count) * 36, gpu::MemoryKind::readback, "statistics readback");
    stats_capacity = count;
}

void FrameResources::ensure_carry(uint32_t pixels) {
    pixels = std::max(pixels, 1u);
    if (pixels <= carry_capacity) return;
    const auto& c = *context;
    replace(carried_color, c, uint64_t(pixels) * 16, "carried colour and transmittance");
    replace(carried_depth_count, c, uint64_t(pixels) * 8, "carried depth sums and contributor counts");
    carry_capacity = pixels;
}

void FrameResources::ensure_packed(uint32_t pixels) {
    pixels = std::max(pixels, 1u);
    if (pixels <= packed_capacity) return;
    replace(packed, *context, uint64_t(pixels) * 4, "8-bit image");
    packed_capacity = pixels;
}

bool FrameResources::fits(uint32_t gaussians, uint32_t pixels, uint32_t tiles, uint32_t entries) const {
    return std::max(gaussians, 1u) <= gaussian_capacity && std::max(pixels, 1u) <= pixel_capacity &&
           tiles <= tile_capacity && std::max(entries, 1u) <= entry_capacity;
}

uint64_t FrameResources::bytes_for(const gpu::Context& context, uint32_t gaussians, uint32_t entries, uint32_t pixels,
                                   uint32_t tiles, bool carry) {
    gaussians = std::max(gaussians, 1u);
    entries = std::max(entries, 1u);
    pixels = std::max(pixels, 1u);
    return sizeof(CameraParams) + kCounterCount * sizeof(uint32_t) + uint64_t(gaussians) * 80 +
           gpu::PrefixScan::Scratch::bytes_for(context, gaussians) + uint64_t(entries) * 8 +
           gpu::RadixSort::Scratch::bytes_for(context, std::max(gaussians, entries)) + image_bytes(pixels, tiles, carry);
}

uint64_t FrameResources::image_bytes(uint32_t pixels, uint32_t tiles, bool carry) {
    return uint64_t(pixels) * 24 + uint64_t(tiles) * 8 + (carry ? uint64_t(pixels) * kCarryBytesPerPixel : 0);
}

VkDeviceSize FrameResources::readback_bytes(uint32_t pixels) {
    return uint64_t(pixels) * 24 + kCounterCount * sizeof(uint32_t);
}

uint64_t FrameResources::device_bytes() const {
    uint64_t total = 0;
    for (const gpu::Buffer* b : {&camera, &counters, &means_depth, &footprints, &colors, &tiles_touched,
                                 &depth_keys, &depth_values,
                                 &entry_offsets, &tile_keys, &tile_values, &color_alpha, &depth, &contributors,
                                 &ranges, &packed, &stat_weight, &stat_max_weight, &stat_pixels,
                                 &stat_centre_weight, &carried_color, &carried_depth_count})
        total += b->size();
    if (scan_scratch) total += scan_scratch->device_bytes();
    if (sort_scratch) total += sort_scratch->device_bytes();
    return total;
}

shader::render::BlendFrame blend_frame(const FrameResources& f) {
    return {.camera = f.camera.address(),
            .ranges = f.ranges.address(),
            .tile_values = f.tile_values.address(),
            .footprints = f.footprints.address(),
            .colors = f.colors.address(),
            .out_color_alpha = f.color_alpha.address(),
            .out_depth = f.depth.address(),
            .out_contributors = f.contributors.address()};
}

}  // namespace vksplat::render
