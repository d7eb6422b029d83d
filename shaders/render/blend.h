// The blend variants (blend.comp, blend_stats.comp, blend_carry.comp, blend_stats_carry.comp,
// recorded by src/render/renderer.cpp, Renderer::Impl::record_blend_pass; blend_train.comp,
// recorded by src/train/differentiable_renderer.cpp), all one body (blend_body.glsl) chosen by
// three flags a shader defines before including this:
// - GATHER_STATS 1 (blend_stats*.comp): measure each Gaussian's contribution (RenderSettings::gather_stats).
// - CARRY_STATE 1 (blend_carry.comp, blend_stats_carry.comp): one depth-ordered chunk of a frame
//   too large for the memory budget. The pixel state is loaded from the previous chunk and, except
//   after the last chunk, stored for the next one instead of the finished pixel (the CARRY_ blocks).
// - TRAIN_OUTPUTS 1 (blend_train.comp): also write what the backward pass (blend_backward.glsl)
//   replays each pixel from: its final transmittance, exactly (1 - alpha loses it near 1e-4), and
//   the end of the part of its tile's list it walked (one past the last splat it blended).
// Each variant's push is the frame's buffers (BlendFrame) followed by the parts its flags add.
#ifndef VKSPLAT_RENDER_BLEND_H
#define VKSPLAT_RENDER_BLEND_H

#include "shaders/common/buffers.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"

SHADER_NAMESPACE_BEGIN(render)

#ifndef __cplusplus
#ifndef GATHER_STATS
#error define GATHER_STATS before including blend.h
#endif
#ifndef CARRY_STATE
#define CARRY_STATE 0
#endif
#ifndef TRAIN_OUTPUTS
#define TRAIN_OUTPUTS 0
#endif
#endif

// carry_flags of the chunk variants.
SHADER_CONST(uint, CARRY_LOAD, 1u)  // start from the carried state (every chunk but the first)
SHADER_CONST(uint, CARRY_LAST, 2u)  // write the finished pixel (background added) instead of the state

// The frame's buffers every variant reads and writes.
struct BlendFrame {
    CameraBuffer camera;
    UVec2s ranges;
    Uints tile_values;
    Footprints footprints;
    Vec4s colors;            // rgb and view depth
    Vec4s out_color_alpha;   // rgb + background * T, and alpha = 1 - T
    Floats out_depth;        // expected depth of the blended splats
    Uints out_contributors;  // splats blended into the pixel
};
struct BlendPush {
    BlendFrame blend;
};

// TRAIN_OUTPUTS: what the backward pass replays each pixel from.
struct BlendTrainOutputs {
    Floats out_transmittance;  // final T
    Uints out_last;            // one past the position (in the tile's list) of the last splat blended
};
struct BlendTrainPush {
    BlendFrame blend;
    BlendTrainOutputs train;
};

// CARRY_STATE: two buffers and a word, so that even the statistics variant stays within the 128
// bytes of push constants every device has.
struct BlendCarry {
    Vec4s carried_color;        // colour so far (rgb, no background) and transmittance (a)
    Vec2s carried_depth_count;  // sum of depth * weight so far; splats blended so far as uint
                                // bits, with CARRY_STOPPED once the pixel stopped
    uint carry_flags;           // CARRY_LOAD | CARRY_LAST
};
struct BlendCarryPush {
    BlendFrame blend;
    BlendCarry carry;
};

#ifdef __cplusplus
BUFFER_REFERENCE(Uint64s, std::uint64_t, 8)
#elif GATHER_STATS
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Uint64s { uint64_t v[]; };
#endif

// GATHER_STATS (64-bit integers, so GLSL declares these only for the statistics variants).
#if defined(__cplusplus) || GATHER_STATS
struct BlendStats {
    Uint64s stat_weight;       // per Gaussian: sum of alpha * T (fixed point)
    Uints stat_max_weight;     // per Gaussian: max alpha * T as float bits (non-negative, so uint order)
    Uints stat_pixels;         // per Gaussian: pixels where alpha >= 1/255
    Uints stat_centre_weight;  // per Gaussian: alpha * T at the pixel holding its centre (float bits)
};
struct BlendStatsPush {
    BlendFrame blend;
    BlendStats stats;
};
struct BlendStatsCarryPush {
    BlendFrame blend;
    BlendStats stats;
    BlendCarry carry;
};
#endif

SHADER_NAMESPACE_END

#endif
