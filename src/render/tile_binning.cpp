#include "render/tile_binning.hpp"

#include <bit>
#include <string>

#include "render/passes.hpp"
#include "shaders/clear_words.spv.h"
#include "shaders/emit_tile_entries.spv.h"
#include "shaders/indirect_args.spv.h"
#include "shaders/preprocess.spv.h"
#include "shaders/tile_ranges.spv.h"
#include "vksplat/error.hpp"

namespace vksplat::render {

uint32_t tile_key_bits(uint32_t tiles) { return static_cast<uint32_t>(std::bit_width(tiles)); }

void check_entries_sortable(uint32_t needed) {
    if (needed >= gpu::PrefixScan::saturated_sum)
        throw GpuError("view needs at least " + std::to_string(needed) +
                       " tile entries, more than one frame can sort (fewer or smaller Gaussians in view, or a "
                       "smaller image)");
}

TileBinning::TileBinning(const gpu::Context& c)
    : clear_words_(c, gpu::spirv_words(clear_words_spv), sizeof(ClearWordsPush), {}, "clear_words"),
      preprocess_(c, gpu::spirv_words(preprocess_spv), sizeof(PreprocessPush), {}, "preprocess"),
      indirect_args_(c, gpu::spirv_words(indirect_args_spv), sizeof(IndirectArgsPush), {}, "indirect_args"),
      emit_tile_entries_(c, gpu::spirv_words(emit_tile_entries_spv), sizeof(EmitTileEntriesPush), {},
                         "emit_tile_entries"),
      tile_ranges_(c, gpu::spirv_words(tile_ranges_spv), sizeof(TileRangesPush), {}, "tile_ranges"),
      scan_(c),
      sort_(c) {}

void TileBinning::record(gpu::CommandStream& stream, FrameResources& f, const CameraParams& params,
                         const SceneAddresses& scene) const {
    const uint32_t n = scene.count;
    const uint32_t tiles_x = params.size[2], tiles_y = params.size[3];
    const auto counter = [&](Counter slot) { return f.counters.address() + slot * sizeof(uint32_t); };

    stream.update(f.camera, &params, sizeof(params));
    uint32_t initial_counters[kCounterCount] = {};
    initial_counters[kCounterGaussians] = n;
    stream.update(f.counters, initial_counters, sizeof(initial_counters));
    // The depth sort takes every Gaussian, the culled ones keyed to sort last (preprocess.comp):
    // its count is known from the start, so where it runs one sweep its setup is written here and
    // preprocess counts the keys' digits.
    const auto depth_digits = sort_.record_host_setup(stream, f.depth_keys, f.depth_values, n, 32, *f.sort_scratch);
    stream.barrier();

    // Each kernel below waits for the one before (a few microseconds apiece however little they
    // do), so the scans' and sorts' setups run beside earlier kernels as soon as their counts are known.
    record_preprocess(stream, preprocess_,
                      {f.camera.address(), scene.params, scene.sh, f.means_depth.address(), f.footprints.address(),
                       f.colors.address(), f.tiles_touched.address(),
                       f.depth_keys.address(), f.depth_values.address(), f.counters.address(),
                       depth_digits.value_or(gpu::RadixSort::DigitCounting{})},
                      n);
    // Tiles that get no entries keep an empty range (tile_ranges.comp).
    record_clear_words(stream, clear_words_, {f.ranges.address(), 2 * tiles_x * tiles_y, 0});
    if (!depth_digits)
        sort_.record_setup(stream, f.depth_keys, f.depth_values, counter(kCounterGaussians), *f.sort_scratch);
    stream.barrier();
    stream.mark("preprocess");

    record_indirect_args(stream, indirect_args_,
                         {counter(kCounterVisible), counter(kCounterVisible), counter(kCounterVisibleArgs),
                          f.gaussian_capacity, 256});
    scan_.record_setup(stream, counter(kCounterVisible), *f.scan_scratch);
    sort_.record(stream, f.depth_keys, f.depth_values, 32, *f.sort_scratch, depth_digits.has_value());
    stream.barrier();
    stream.mark("depth sort");

    // Tile counts scanned in depth order (the drawn splats come first) hand out entry slots front
    // to back: entries are then emitted already sorted by depth within every tile, and the tile
    // sort only needs to be stable on the tile bits.
    scan_.record(stream, f.tiles_touched.address(), f.entry_offsets.address(), counter(kCounterEntriesNeeded),
                 *f.scan_scratch, f.depth_values.address());
    stream.barrier();
    record_indirect_args(stream, indirect_args_,
                         {counter(kCounterEntriesNeeded), counter(kCounterEntries), counter(kCounterEntryArgs),
                          f.entry_capacity, 256 * kTileRangeEntriesPerInvocation});
    record_emit_tile_entries(stream, emit_tile_entries_,
                             {f.camera.address(), f.counters.address(), f.depth_values.address(),
                              f.entry_offsets.address(), f.footprints.address(), f.tile_keys.address(),
                              f.tile_values.address()},
                             f.counters, kCounterVisibleArgs * sizeof(uint32_t));
    // The sort clamps the entries needed to what the tile buffers hold, as indirect_args does.
    sort_.record_setup(stream, f.tile_keys, f.tile_values, counter(kCounterEntriesNeeded), *f.sort_scratch);
    stream.barrier();
    stream.mark("tile entries");

    // A stable sort on just the tile bits keeps each tile's entries in depth order.
    sort_.record(stream, f.tile_keys, f.tile_values, tile_key_bits(tiles_x * tiles_y), *f.sort_scratch);
    stream.barrier();
    stream.mark("tile sort");

    record_tile_ranges(stream, tile_ranges_,
                       {f.counters.address(), f.tile_keys.address(), f.ranges.address(), tiles_x * tiles_y},
                       f.counters, kCounterEntryArgs * sizeof(uint32_t));
    stream.barrier();
    stream.mark("ranges");
}

}  // namespace vksplat::render
