#pragma once
// FrameResources: the device buffers one frame works in, sized by the scene (per-Gaussian
// arrays), the image (pixels and tiles) and the tile-entry capacity. Each group is reallocated
// only when it must grow, so rendering many views of one scene allocates once.
#include <cstdint>

#include "gpu/buffer.hpp"
#include "gpu/prefix_scan.hpp"
#include "gpu/radix_sort.hpp"
#include "shaders/render/blend.h"

namespace vksplat::render {

struct FrameResources {
    const gpu::Context* context = nullptr;

    // Per frame.
    gpu::Buffer camera;    // CameraParams
    gpu::Buffer counters;  // Counter slots (shaders/render/frame.h)

    // Per Gaussian (capacity gaussian_capacity).
    uint32_t gaussian_capacity = 0;
    gpu::Buffer means_depth, footprints, colors, tiles_touched;
    gpu::Buffer depth_keys, depth_values, entry_offsets;
    std::unique_ptr<gpu::PrefixScan::Scratch> scan_scratch;

    // Per tile entry (capacity entry_capacity).
    uint32_t entry_capacity = 0;
    gpu::Buffer tile_keys, tile_values;
    std::unique_ptr<gpu::RadixSort::Scratch> sort_scratch;  // serves the depth and the tile sort

    // Per-Gaussian statistics (allocated on the first frame that asks for them): weight 8, max
    // weight 4, pixels 4 and centre weight 4 bytes.
    static constexpr uint64_t kStatsBytesPerGaussian = 20;
    uint32_t stats_capacity = 0;
    gpu::Buffer stat_weight, stat_max_weight, stat_pixels, stat_centre_weight;
    gpu::Buffer stats_readback;  // host-visible: means_depth, weight, max weight, pixels, centre weight

    // Per pixel and per tile.
    uint32_t pixel_capacity = 0, tile_capacity = 0;
    gpu::Buffer color_alpha, depth, contributors, ranges;
    // Host-visible: color_alpha, depth, contributors, then the counters. Apart from the image's
    // device buffers: the trainer never reads a frame back, and pinned host memory is slow to
    // allocate and free at each of its densification events.
    uint32_t readback_capacity = 0;
    gpu::Buffer readback;

    // Per-pixel state carried from one depth-ordered chunk to the next (frames larger than the
    // memory budget; allocated on the first such frame): colour and transmittance 16, depth sum
    // and contributor count 8 bytes.
    static constexpr uint64_t kCarryBytesPerPixel = 24;
    uint32_t carry_capacity = 0;
    gpu::Buffer carried_color, carried_depth_count;

    // Frames recorded into an application's command buffer (Renderer::record).
    uint32_t packed_capacity = 0;
    gpu::Buffer packed;              // 8-bit RGBA words for an 8-bit target (allocated on first use)
    gpu::Buffer recorded_counters;   // host-visible: the counters of the last recorded frame to finish

    explicit FrameResources(const gpu::Context& context);
    void ensure_gaussians(uint32_t count);
    void ensure_entries(uint32_t count);
    void ensure_image(uint32_t pixels, uint32_t tiles);
    void ensure_readback(uint32_t pixels);
    void ensure_stats(uint32_t count);
    void ensure_packed(uint32_t pixels);
    void ensure_carry(uint32_t pixels);
    // Frees every buffer (sized by the scene, the tile entries or the image), for a caller that
    // needs the memory for a while: the trainer's densification holds the old and the new scene's
    // arrays in turn. The next ensure_* calls allocate them anew.
    void release();
    // Whether the ensure_* calls for these sizes would keep every buffer (reallocate none).
    bool fits(uint32_t gaussians, uint32_t pixels, uint32_t tiles, uint32_t entries) const;
    uint64_t device_bytes() const;
    // The device_bytes() of fresh resources after ensure_gaussians, ensure_entries, ensure_image
    // (and ensure_carry) for these sizes: what a frame needs besides the scene.
    static uint64_t bytes_for(const gpu::Context& context, uint32_t gaussians, uint32_t entries, uint32_t pixels,
                              uint32_t tiles, bool carry);
    // The part of bytes_for that grows with the image (colour, depth, contributors, tile ranges,
    // and the carried state): what a frame of this size needs however few Gaussians it draws.
    static uint64_t image_bytes(uint32_t pixels, uint32_t tiles, bool carry);
    static VkDeviceSize readback_bytes(uint32_t pixels);
};

// The frame's buffers as every blend variant reads and writes them (shaders/render/blend.h).
shader::render::BlendFrame blend_frame(const FrameResources& frame);

}  // namespace vksplat::render
