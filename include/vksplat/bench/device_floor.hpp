#pragma once
// The physical floor a frame is measured against: what this device can do at best, measured on
// it, and what a frame must at least move and sort. A frame's time over its floor says how much
// is left to win, and where.
#include <cstdint>

#include "vksplat/gpu/context.hpp"

namespace vksplat::bench {

struct DeviceRates {
    // A shader copying a large buffer with every invocation, bytes read plus bytes written per ms.
    double copy_bytes_per_ms = 0;
    // Our radix sort of (uint32 key, uint32 value) pairs by all 32 key bits (4 digit passes).
    double sort_pairs_per_ms = 0;
    uint64_t copy_bytes = 0;  // size of the copied buffer
    uint32_t sort_pairs = 0;  // pairs in the timed sort
    // One dispatch that waits on the previous one through the renderer's barrier, with (almost)
    // nothing to do, in ms: what each kernel of a frame costs however little it has to do, so a
    // frame of K kernels in a chain cannot take less than K times this.
    double dependent_dispatch_ms = 0;
};

struct RateOptions {
    uint64_t copy_bytes = 512ull << 20;  // < 64 GiB: the shader counts 16-byte words in 32 bits
    uint32_t sort_pairs = 16u << 20;
    int repetitions = 10;  // the median of these is reported
};

// Times a large shader copy and a large sort with timestamp queries. Throws GpuError when the
// queue has no timestamps (lavapipe has them).
DeviceRates measure_device_rates(const gpu::Context& context, const RateOptions& options = {});

// What one frame cannot avoid.
struct FrameWork {
    uint64_t scene_bytes = 0;    // every Gaussian's parameters and SH, read once
    uint32_t visible = 0;        // splats sorted by depth (32-bit keys)
    uint32_t tile_entries = 0;   // (tile, splat) pairs sorted by tile
    uint32_t tile_key_bits = 0;  // bits of the tile keys
    uint64_t pixels = 0;
};

struct FrameFloor {
    uint64_t bytes = 0;       // that must move: scene read, splats read per tile entry, image written
    double memory_ms = 0;     // bytes at the copy rate
    double sort_ms = 0;       // both sorts at the measured sort rate, scaled by their digit passes
    double total_ms() const { return memory_ms + sort_ms; }
};

// Bytes: scene_bytes + 48 per tile entry (the splat's mean, conic, opacity and colour read by the
// blend) + 16 per pixel (RGBA written). Sorts: visible pairs at the 32-bit rate plus tile entries
// at that rate times (tile passes / 4).
FrameFloor frame_floor(const FrameWork& work, const DeviceRates& rates);

}  // namespace vksplat::bench
