#ifndef GATHER_STATS
#error define GATHER_STATS before including blend_body.glsl
#endif
// The blend pass, included by every blend variant (shaders/render/blend.h says which flags choose
// what) after its push constants `pc`, so that the plain pipeline holds no statistics code (and
// needs no 64-bit integers) at all.
//
// Blend: one workgroup per 16x16 tile, one thread per pixel. The tile's depth-sorted splats are
// fetched cooperatively in batches into shared memory, then every pixel composites them front
// to back exactly as the reference's renderCUDA: skip where power > 0 or alpha < 1/255, stop
// before the transmittance would fall below 1e-4, and add the background times what remains.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#if GATHER_STATS
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_ballot : require
#endif

#include "vksplat/constants.hpp"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/render/tile_blocks.glsl"
#include "shaders/render/tile_culling.glsl"

layout(local_size_x = 256) in;
const uint BATCH = 256;  // = threads per workgroup: one fetch per thread per batch
// Splats a pixel reads (alpha, colour, depth) before compositing them: their loads and exp chains
// overlap, and the compositing that follows, in list order exactly as one at a time, waits on no
// load. H200, lego tiled 5x5 blend: 2.45 ms with 2, 2.20 with 3, 2.06 with 4, 2.00 with 8, 1.95
// with 8 and the colours read ahead too (105 registers: the 2 workgroups per multiprocessor that
// 70 allowed); 12 spilled to local memory.
const uint UNROLL = 8;
#include "shaders/render/block_hit_lists.glsl"

#if GATHER_STATS
// alpha * T in 32.32 fixed point: integer atomics make the sums the same every run.
const float WEIGHT_SCALE = 4294967296.0;
#endif

#if CARRY_STATE
const uint CARRY_STOPPED = 0x80000000u;
#endif

#if GATHER_STATS
// Only the one pixel nearest the projected centre writes it, so no atomic is needed; it stays 0
// where the pixel finished before reaching the splat (occluded) or the splat is too faint there.
//
// The pixels of a subgroup composite the same splat at the same time, and a large splat covers
// them all: where every invocation of the subgroup records the same splat, they are summed in
// the subgroup first and one invocation adds the total, instead of every pixel contending for the
// same address (per-pixel atomics made scoring snowmiku's views cost 3x rendering them on an
// H200). Where fewer record it (small splats: most of lego's), per-pixel atomics are uncontended
// and the reductions would cost more than they save. H200, --stats over 13 views, plain frames
// 0.513 ms (snowmiku) and 0.791 ms (lego): summing from any 1 / 16 / 24 / 32 recording
// invocations, snowmiku 1.174 / 0.993 / 0.944 / 0.897 ms, lego 2.237 / 1.45-1.58 / 1.39-1.54 ms;
// never, 1.536 and 1.38 ms. The float sum of a subgroup is rounded to fixed point once, so
// totals depend on the subgroup size by float rounding, and never on timing.
// On a CPU implementation (lavapipe) the host turns this off: there uncontended atomics are cheap
// and the subgroup reductions are not (snowmiku --stats 2.59 s per view with atomics, 3.34 s summed).
layout(constant_id = 0) const bool SUM_IN_SUBGROUP = true;

void record_stats(uint gaussian, float weight, vec2 mean, uvec2 pixel) {
    if (all(equal(uvec2(ivec2(floor(mean + 0.5))), pixel))) pc.stats.stat_centre_weight.v[gaussian] = floatBitsToUint(weight);
    // True only where every invocation is active and at this splat (inactive ones set no bit).
    if (SUM_IN_SUBGROUP &&
        subgroupBallotBitCount(subgroupBallot(gaussian == subgroupBroadcastFirst(gaussian))) == gl_SubgroupSize) {
        const float weight_sum = subgroupAdd(weight);
        const uint max_bits = subgroupMax(floatBitsToUint(weight));
        const uint pixels = subgroupAdd(1u);
        if (subgroupElect()) {
            if (weight_sum > 0.0) atomicAdd(pc.stats.stat_weight.v[gaussian], uint64_t(weight_sum * WEIGHT_SCALE));
            if (max_bits > 0u) atomicMax(pc.stats.stat_max_weight.v[gaussian], max_bits);
            atomicAdd(pc.stats.stat_pixels.v[gaussian], pixels);
        }
        return;
    }
    if (weight > 0.0) {
        atomicAdd(pc.stats.stat_weight.v[gaussian], uint64_t(weight * WEIGHT_SCALE));
        atomicMax(pc.stats.stat_max_weight.v[gaussian], floatBitsToUint(weight));
    }
    atomicAdd(pc.stats.stat_pixels.v[gaussian], 1u);
}
#endif

// Only xy is used; as vec4s the blend measured faster than as vec2s (H200, lego tiled 5x5: 1.979 vs
// 1.992 ms).
shared vec4 batch_mean[BATCH];
shared vec4 batch_conic_opacity[BATCH];
shared vec4 batch_color_depth[BATCH];
#if GATHER_STATS
shared uint batch_gaussian[BATCH];
#endif
shared uint finished_pixels;

// What a pixel has accumulated so far.
struct PixelState {
    vec3 color;
    float transmittance;
    float depth_sum;
    uint contributors;
    uint last;  // one past the list position of the last splat blended (TRAIN_OUTPUTS)
    bool done;  // transmittance would have fallen below MIN_TRANSMITTANCE: nothing more is added
};

// Alpha of the batch's splat j at the pixel, or 0 where the reference skips it.
float splat_alpha(uint j, vec2 pixel_f) {
    const vec4 conic_o = batch_conic_opacity[j];
    const vec2 d = batch_mean[j].xy - pixel_f;
    const float power = -0.5 * (conic_o.x * d.x * d.x + conic_o.z * d.y * d.y) - conic_o.y * d.x * d.y;
    if (power > 0.0) return 0.0;
    return min(MAX_ALPHA, conic_o.w * exp(power));
}

// Composites the batch's splat j behind what the pixel holds, as the reference does.
void blend_splat(uint j, uint position, float alpha, vec4 color_depth, uvec2 pixel, inout PixelState state) {
    if (alpha < MIN_ALPHA) return;
    const float next_transmittance = state.transmittance * (1.0 - alpha);
    if (next_transmittance < MIN_TRANSMITTANCE) {
        // It stops the pixel without adding to it: still a pixel it decides.
#if GATHER_STATS
        record_stats(batch_gaussian[j], 0.0, batch_mean[j].xy, pixel);
#endif
        state.done = true;
        return;
    }
    const float weight = alpha * state.transmittance;
#if GATHER_STATS
    record_stats(batch_gaussian[j], weight, batch_mean[j].xy, pixel);
#endif
    state.color += color_depth.rgb * weight;
    state.depth_sum += color_depth.w * weight;
    state.transmittance = next_transmittance;
    ++state.contributors;
    state.last = position + 1u;
}

void main() {
    const CameraParams cam = pc.blend.camera.c;
    const uvec2 tile_origin = gl_WorkGroupID.xy * uvec2(TILE_WIDTH, TILE_HEIGHT);
    const uvec2 pixel = tile_origin + pixel_in_tile(gl_LocalInvocationIndex);
    const uint my_block = block_of(gl_LocalInvocationIndex);
    const uint slot = batch_slot();
    const bool inside = pixel.x < cam.size.x && pixel.y < cam.size.y;
    const vec2 pixel_f = vec2(pixel);
    const uvec2 range = pc.blend.ranges.v[gl_WorkGroupID.y * cam.size.z + gl_WorkGroupID.x];

    PixelState state = PixelState(vec3(0.0), 1.0, 0.0, 0u, 0u, !inside);
#if CARRY_STATE
    if (inside && (pc.carry.carry_flags & CARRY_LOAD) != 0u) {
        const uint index = pixel.y * cam.size.x + pixel.x;
        const vec4 carried = pc.carry.carried_color.v[index];
        const vec2 depth_count = pc.carry.carried_depth_count.v[index];
        const uint contributors = floatBitsToUint(depth_count.y);
        // A pixel that stopped stays stopped.
        state = PixelState(carried.rgb, carried.a, depth_count.x, contributors & ~CARRY_STOPPED, 0u,
                           (contributors & CARRY_STOPPED) != 0u);
    }
#endif

    for (uint start = range.x; start < range.y; start += BATCH) {
        // The whole tile stops once every pixel is done (a uniform decision, so the barriers
        // below stay in uniform control flow).
        if (gl_LocalInvocationIndex == 0u) finished_pixels = 0u;
        barrier();
        if (state.done) atomicAdd(finished_pixels, 1u);
        uint touched = 0u;
        if (start + slot < range.y) {
            const uint gaussian = pc.blend.tile_values.v[start + slot];
            const Footprint footprint = pc.blend.footprints.v[gaussian];
            const vec2 mean = footprint_mean(footprint);
            const vec4 conic_opacity = footprint_conic_opacity(footprint);
            batch_mean[slot] = vec4(mean, 0.0, 0.0);
            batch_conic_opacity[slot] = conic_opacity;
            batch_color_depth[slot] = pc.blend.colors.v[gaussian];
            touched = touched_blocks(mean, conic_opacity, tile_origin);
#if GATHER_STATS
            batch_gaussian[slot] = gaussian;
#endif
        }
        barrier();
        if (finished_pixels == BATCH) break;
        list_block_hits(slot, touched);

        // The splats that miss the pixel's block have alpha < 1/255 there: skipping them leaves
        // the pixel exactly as the reference's walk of the whole list does.
        const uint hits = block_hit_count[my_block];
        for (uint k = 0u; !state.done && k < hits; k += UNROLL) {
            uint j[UNROLL];
            float alpha[UNROLL];
            vec4 color_depth[UNROLL];
            for (uint u = 0u; u < UNROLL; ++u) {
                j[u] = block_hits[my_block * BATCH + min(k + u, hits - 1u)];  // past the end: evaluated, not composited
                alpha[u] = splat_alpha(j[u], pixel_f);
                color_depth[u] = batch_color_depth[j[u]];
            }
            // A constant trip count, so that the arrays stay in registers.
            for (uint u = 0u; u < UNROLL; ++u)
                if (k + u < hits && !state.done) blend_splat(j[u], start + j[u], alpha[u], color_depth[u], pixel, state);
        }
        barrier();  // the next batch overwrites shared memory
    }

    if (inside) {
        const uint index = pixel.y * cam.size.x + pixel.x;
#if CARRY_STATE
        if ((pc.carry.carry_flags & CARRY_LAST) == 0u) {
            pc.carry.carried_color.v[index] = vec4(state.color, state.transmittance);
            pc.carry.carried_depth_count.v[index] =
                vec2(state.depth_sum, uintBitsToFloat(state.contributors | (state.done ? CARRY_STOPPED : 0u)));
            return;
        }
#endif
        const float alpha = 1.0 - state.transmittance;
        pc.blend.out_color_alpha.v[index] = vec4(state.color + state.transmittance * cam.background.rgb, alpha);
        pc.blend.out_depth.v[index] = alpha > 0.0 ? state.depth_sum / alpha : 0.0;
        pc.blend.out_contributors.v[index] = state.contributors;
#if TRAIN_OUTPUTS
        pc.train.out_transmittance.v[index] = state.transmittance;
        pc.train.out_last.v[index] = state.last;
#endif
    }
}
