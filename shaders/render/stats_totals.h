// stats_totals.comp, recorded by src/render/stats_totals.cpp (Renderer::render_stats_totals): adds
// one view's per-Gaussian blend statistics (blend.h's BlendStats) into totals over many views, on
// the device, so that scoring a few hundred views reads back the totals once instead of every
// view's statistics (36 bytes a Gaussian a view, whose copy and unpacking cost more than the frame).
#ifndef VKSPLAT_RENDER_STATS_TOTALS_H
#define VKSPLAT_RENDER_STATS_TOTALS_H

#include "shaders/render/blend.h"

SHADER_NAMESPACE_BEGIN(render)

// A radius counts at most this many pixels in the sum of squared radii: far beyond any image, and
// so small that 2^16 views of squares stay within 64 bits.
SHADER_CONST(uint, TOTALS_MAX_RADIUS, 1u << 24)

// This view's statistics as the blend left them, and the frame's counters: a frame whose tile
// entries overflowed their buffer is drawn again, so the pass adds nothing for it.
struct StatsTotalsView {
    Vec4s means_depth;      // w: the radius in pixels, 0 where the Gaussian was culled
    Uint64s stat_weight;    // 32.32 fixed point
    Uints stat_max_weight;  // float bits
    Uints stat_pixels;
    Uints counters;         // COUNTER_ENTRIES_NEEDED against entry_capacity
};

// Per Gaussian, over the views added.
struct StatsTotalsSums {
    Uint64s weight_low;     // sum of the 32.32 weights: 96 bits, low 64 here
    Uints weight_high;      // and the high 32 (a weight of 2^32 in all overflows 64 bits)
    Uints max_weight;       // float bits
    Uint64s pixels;
    Uint64s radius_squared; // sum of the squared radii of the views where it was visible
    Uints views_visible;
};

struct StatsTotalsPush {
    StatsTotalsView view;
    StatsTotalsSums sums;
    uint count;
    uint entry_capacity;
};

SHADER_NAMESPACE_END

#endif
