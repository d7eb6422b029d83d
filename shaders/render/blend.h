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
// In GLSL the variant's push struct is declared; C++ sees all five.
#ifndef VKSPLAT_RENDER_BLEND_H
#define VKSPLAT_RENDER_BLEND_H

#include "shaders/common/buffers.h"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"

SHADER_NAMESPACE_BEGIN(render)

// carry_flags of the chunk variants.
SHADER_CONST(uint, CARRY_LOAD, 1u)  // start from the carried state (every chunk but the first)
SHADER_CONST(uint, CARRY_LAST, 2u)  // write the finished pixel (background added) instead of the state

#ifdef __cplusplus

BUFFER_REFERENCE(Uint64s, std::uint64_t, 8)

#define BLEND_PUSH BlendPush
#define TRAIN_OUTPUTS 0
#define GATHER_STATS 0
#define CARRY_STATE 0
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH
#undef GATHER_STATS
#define BLEND_PUSH BlendStatsPush
#define GATHER_STATS 1
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH
#undef CARRY_STATE
#define BLEND_PUSH BlendStatsCarryPush
#define CARRY_STATE 1
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH
#undef GATHER_STATS
#define BLEND_PUSH BlendCarryPush
#define GATHER_STATS 0
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH
#undef CARRY_STATE
#undef TRAIN_OUTPUTS
#define BLEND_PUSH BlendTrainPush
#define CARRY_STATE 0
#define TRAIN_OUTPUTS 1
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH
#undef GATHER_STATS
#undef CARRY_STATE
#undef TRAIN_OUTPUTS

#else  // GLSL: the variant the shader's flags choose

#ifndef GATHER_STATS
#error define GATHER_STATS before including blend.h
#endif
#ifndef CARRY_STATE
#define CARRY_STATE 0
#endif
#ifndef TRAIN_OUTPUTS
#define TRAIN_OUTPUTS 0
#endif
#if GATHER_STATS
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Uint64s { uint64_t v[]; };
#endif
#if GATHER_STATS && CARRY_STATE
#define BLEND_PUSH BlendStatsCarryPush
#elif GATHER_STATS
#define BLEND_PUSH BlendStatsPush
#elif CARRY_STATE
#define BLEND_PUSH BlendCarryPush
#elif TRAIN_OUTPUTS
#define BLEND_PUSH BlendTrainPush
#else
#define BLEND_PUSH BlendPush
#endif
#include "shaders/render/blend_push.h"
#undef BLEND_PUSH

#endif

SHADER_NAMESPACE_END

#endif
