#include "render/tile_binning.hpp"

#include <bit>
#include <string>

#include "shaders/render/clear_words.kernel.hpp"
#include "shaders/render/emit_tile_entries.kernel.hpp"
#include "shaders/render/indirect_args.kernel.hpp"
#include "shaders/render/preprocess.kernel.hpp"
#include "shaders/render/tile_ranges.kernel.hpp"
#include "vksplat/error.hpp"

namespace vksplat::render {

using namespace shader::render;

uint32_t tile_key_bits(uint32_t tiles) { return static_cast<uint32_t>(std::bit_width(tiles)); }

void check_entries_sortable(uint32_t needed) {
    if (needed >= gpu::PrefixScan::saturated_sum)
        throw GpuError("view needs at least " + std::to_string(needed) +
                       " tile entries, more than one frame can sort (fewer or smaller Gaussians in view, or a "
                       "smaller image)");
}

TileBinning::TileBinning(const gpu::Context& c) : TileBinning(c, std::make_unique<gpu::Kernel<PreprocessKernel>>(c)) {}

TileBinning::TileBinning(const gpu::Context& c, std::unique_ptr<PreprocessPipeline> preprocess)
    : clear_words_(std::make_unique<gpu::Kernel<ClearWordsKernel>>(c)),
      preprocess_(std::move(preprocess)),
      indirect_args_(std::make_unique<gpu::Kernel<IndirectArgsKernel>>(c)),
      emit_tile_entries_(std::make_unique<gpu::Kernel<EmitTileEntriesKernel>>(c)),
      tile_ranges_(std::make_unique<gpu::Kernel<TileRangesKernel>>(c)),
      scan_(c),
      sort_(c) {}

TileBinning::~TileBinning() = default;

void TileBinning::record(gpu::CommandStream& stream, FrameResources& f, const CameraParams& params,
                         const SceneAddresses& scene) const {
    const uint32_t n = scene.count;
    const uint32_t tiles_x = params.size[2], tiles_y = params.size[3];
    const auto counter = [&](uint32_t slot) { return f.counters.address() + slot * sizeof(uint32_t); };

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
    stream.dispatch(*preprocess_,
                    {.camera = f.camera.address(),
                     .params = scene.params,
                     .sh = scene.sh,
                     .means_depth = f.means_depth.address(),
                     .footprints = f.footprints.address(),
                     .colors = f.colors.address(),
                     .tiles_touched = f.tiles_touched.address(),
                     .depth_keys = f.depth_keys.address(),
                     .depth_values = f.depth_values.address(),
                     .counters = f.counters.address(),
                     .depth_digits = depth_digits.value_or(gpu::RadixSort::DigitCounting{})},
                    gpu::groups_for(n));
    // Tiles that get no entries keep an empty range (tile_ranges.comp).
    const uint32_t range_words = 2 * tiles_x * tiles_y;
    stream.dispatch(*clear_words_, {.words = f.ranges.address(), .count = range_words, .value = 0},
                    gpu::groups_for(range_words));
    if (!depth_digits)
        sort_.record_setup(stream, f.depth_keys, f.depth_values, counter(kCounterGaussians), *f.sort_scratch);
    stream.barrier();
    stream.mark("preprocess");

    stream.dispatch(*indirect_args_,
                    {.count_in = counter(kCounterVisible),
                     .count_out = counter(kCounterVisible),
                     .args = counter(kCounterVisibleArgs),
                     .capacity = f.gaussian_capacity,
                     .per_group = 256},
                    1);
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
    stream.dispatch(*indirect_args_,
                    {.count_in = counter(kCounterEntriesNeeded),
                     .count_out = counter(kCounterEntries),
                     .args = counter(kCounterEntryArgs),
                     .capacity = f.entry_capacity,
                     .per_group = 256 * TILE_RANGES_ENTRIES_PER_INVOCATION},
                    1);
    stream.dispatch_indirect(*emit_tile_entries_,
                             {.camera = f.camera.address(),
                              .counters = f.counters.address(),
                              .depth_values = f.depth_values.address(),
                              .entry_offsets = f.entry_offsets.address(),
                              .footprints = f.footprints.address(),
                              .tile_keys = f.tile_keys.address(),
                              .tile_values = f.tile_values.address()},
                             f.counters, kCounterVisibleArgs * sizeof(uint32_t));
    // The sort clamps the entries needed to what the tile buffers hold, as indirect_args does.
    sort_.record_setup(stream, f.tile_keys, f.tile_values, counter(kCounterEntriesNeeded), *f.sort_scratch);
    stream.barrier();
    stream.mark("tile entries");

    // A stable sort on just the tile bits keeps each tile's entries in depth order.
    sort_.record(stream, f.tile_keys, f.tile_values, tile_key_bits(tiles_x * tiles_y), *f.sort_scratch);
    stream.barrier();
    stream.mark("tile sort");

    stream.dispatch_indirect(*tile_ranges_,
                             {.counters = f.counters.address(),
                              .tile_keys = f.tile_keys.address(),
                              .ranges = f.ranges.address(),
                              .tile_count = tiles_x * tiles_y},
                             f.counters, kCounterEntryArgs * sizeof(uint32_t));
    stream.barrier();
    stream.mark("ranges");
}

}  // namespace vksplat::render
