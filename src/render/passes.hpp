#pragma once
// The render passes. Each is one shader (shaders/<name>.comp) and one small host function that
// fills its push constants (the C++ twin of the shader's Push block) and records the dispatch.
#include <cstdint>

#include "gpu/command_stream.hpp"
#include "gpu/radix_sort.hpp"

namespace vksplat::render {

using Address = VkDeviceAddress;

struct PreprocessPush {
    Address camera, params, sh, means_depth, footprints, colors, tiles_touched, depth_keys, depth_values, counters;
    gpu::RadixSort::DigitCounting depth_digits;  // passes 0: the depth sort counts its own digits
};
void record_preprocess(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const PreprocessPush& push,
                       uint32_t gaussian_count);

struct IndirectArgsPush {
    Address count_in, count_out, args;
    uint32_t capacity, per_group;
};
void record_indirect_args(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                          const IndirectArgsPush& push);

struct EmitTileEntriesPush {
    Address camera, counters, depth_values, entry_offsets, footprints, tile_keys, tile_values;
};
void record_emit_tile_entries(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                              const EmitTileEntriesPush& push, const gpu::Buffer& args, VkDeviceSize args_offset);

struct ClearWordsPush {
    Address words;
    uint32_t count, value;
};
void record_clear_words(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const ClearWordsPush& push);

// Entries one tile_ranges invocation takes (its ENTRIES_PER_INVOCATION): its dispatch is sized by it.
constexpr uint32_t kTileRangeEntriesPerInvocation = 4;
struct TileRangesPush {
    Address counters, tile_keys, ranges;
    uint32_t tile_count;
};
void record_tile_ranges(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const TileRangesPush& push,
                        const gpu::Buffer& args, VkDeviceSize args_offset);

struct BlendPush {
    Address camera, ranges, tile_values, footprints, colors, out_color_alpha, out_depth, out_contributors;
};
// The statistics variant (blend_stats.comp) takes four more buffers after the plain ones.
struct BlendStatsPush {
    BlendPush blend;
    Address stat_weight, stat_max_weight, stat_pixels, stat_centre_weight;
};
// The chunk variants (blend_carry.comp, blend_stats_carry.comp): the carried per-pixel state and
// the CARRY_ flags of blend_body.glsl.
struct CarryPush {
    Address carried_color, carried_depth_count;
    uint32_t flags;
};
struct BlendCarryPush {
    BlendPush blend;
    CarryPush carry;
};
struct BlendStatsCarryPush {
    BlendStatsPush stats;
    CarryPush carry;
};
constexpr uint32_t kCarryLoad = 1, kCarryLast = 2;
void record_blend(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendPush& push,
                  uint32_t tiles_x, uint32_t tiles_y);
void record_blend_carry(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const BlendCarryPush& push,
                        uint32_t tiles_x, uint32_t tiles_y);
void record_blend_stats_carry(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                              const BlendStatsCarryPush& push, uint32_t tiles_x, uint32_t tiles_y);
void record_blend_stats(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline,
                        const BlendStatsPush& push, uint32_t tiles_x, uint32_t tiles_y);

struct PackRgba8Push {
    Address color_alpha, packed;
    uint32_t pixels, bgra;
};
void record_pack_rgba8(gpu::CommandStream& stream, const gpu::ComputePipeline& pipeline, const PackRgba8Push& push);

// Workgroups for a grid-stride loop over `count` elements, 256 per group, at most 65535 groups.
uint32_t groups_for(uint32_t count, uint32_t per_group = 256);

}  // namespace vksplat::render
