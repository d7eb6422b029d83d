// The passes of a frame before the blend, recorded by src/render/tile_binning.cpp
// (TileBinning::record): preprocess.comp, clear_words.comp, indirect_args.comp,
// emit_tile_entries.comp, tile_ranges.comp. Their push constants and the constants the host sizes
// their dispatches by.
#ifndef VKSPLAT_RENDER_TILE_BINNING_H
#define VKSPLAT_RENDER_TILE_BINNING_H

#include "shaders/common/buffers.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/sort/radix_sort.h"

SHADER_NAMESPACE_BEGIN(render)

#ifdef __cplusplus
using sort::DigitCounting;
#endif

// preprocess.comp: one thread per Gaussian, 256 per workgroup.
struct PreprocessPush {
    CameraBuffer camera;
    Vec4s params;         // 3 per Gaussian: (position, opacity), (scale, -), (quaternion w, x, y, z)
    Floats sh;            // [Gaussian][coefficient][rgb], floats or packed halves (cam.sh_half)
    Vec4s means_depth;    // out where cam.write_projection: pixel position (x, y), view depth, radius in pixels
    Footprints footprints;  // out: position, inverse 2D covariance, opacity, tile rectangle
    Vec4s colors;         // out: rgb and the view depth
    Uints tiles_touched;  // out: tiles its alpha >= 1/255 ellipse meets, 0 when not drawn
    Uints depth_keys;     // out: view depth as float bits if drawn, else NOT_DRAWN
    Uints depth_values;   // out: Gaussian index
    Uints counters;       // COUNTER_VISIBLE: drawn splats are added to it
    // Where the depth sort runs one sweep (depth_digits.passes > 0), this kernel does its
    // histogram kernel's work (shaders/sort/radix_digit_counts.glsl): every key's digits are
    // counted into depth_digits.totals and the sort's look-back words emptied.
    DigitCounting depth_digits;
};

// indirect_args.comp (one invocation): a GPU count into dispatch arguments.
struct IndirectArgsPush {
    Uints count_in;
    Uints count_out;              // count clamped to capacity
    DispatchArgsBuffer args;
    uint capacity;
    uint per_group;               // elements one workgroup covers per loop iteration
};

// clear_words.comp: count words set to value, 256 per workgroup.
struct ClearWordsPush {
    Uints words;
    uint count;
    uint value;
};

// emit_tile_entries.comp: dispatched over the visible splats (COUNTER_VISIBLE_ARGS).
struct EmitTileEntriesPush {
    CameraBuffer camera;
    Uints counters;
    Uints depth_values;   // Gaussian indices in depth order
    Uints entry_offsets;  // exclusive scan of the depth-ordered tile counts; the total in COUNTER_ENTRIES_NEEDED
    Footprints footprints;
    Uints tile_keys;      // out: tile index (row-major)
    Uints tile_values;    // out: Gaussian index
};

// tile_ranges.comp: dispatched over the entries (COUNTER_ENTRY_ARGS), each invocation taking
// TILE_RANGES_ENTRIES_PER_INVOCATION of them.
SHADER_CONST(uint, TILE_RANGES_ENTRIES_PER_INVOCATION, 4)
struct TileRangesPush {
    Uints counters;
    Uints tile_keys;
    UVec2s ranges;    // out: per tile
    uint tile_count;  // keys at or past it are padding (tile_culling.glsl) and have no range
};

SHADER_NAMESPACE_END

#endif
