#if !defined(FLOAT_ATOMICS) || !defined(FIXED_POINT_SUMS) || !defined(PER_SPLAT)
#error define FLOAT_ATOMICS, FIXED_POINT_SUMS and PER_SPLAT before including blend_backward.glsl
#endif
// The blend's backward pass, included after its push constants `pc` (BlendBackwardPush,
// shaders/train/differentiable_renderer.h) by blend_backward.comp (FLOAT_ATOMICS 1: the device adds
// floats atomically), blend_backward_cas.comp (0: a compare-and-swap loop, for devices without
// VK_EXT_shader_atomic_float; the same sums, slower, and in either case their order varies),
// blend_backward_fixed.comp (FIXED_POINT_SUMS 1: 64-bit integer sums, the same in any order), and
// their per-splat forms blend_backward_per_splat.comp and blend_backward_per_splat_cas.comp
// (PER_SPLAT 1, below).
//
// One workgroup per tile, one invocation per pixel, the pixels in blend_body.glsl's order. Each
// pixel replays the splats it walked (list positions below its `last`) back to front, recovering
// the transmittance in front of each splat from the final one (T_j = T_{j+1} / (1 - alpha_j)) and
// the colour blended behind it, and so the exact derivative of its colour with respect to each
// splat's colour, opacity, 2D mean and conic (replay_splat). Alpha is recomputed with blend_body's
// formula, so the splats skipped there (alpha < 1/255) are skipped here. Unlike the reference, a
// splat whose alpha was clamped at 0.99 gets no gradient through opacity or shape: the clamp is
// flat there. The gradients go to the splat's totals (shaders/train/parameter_layout.h's
// SPLAT_GRAD_ slots) by atomic adds. Like the blend, a pixel walks only its block's list of the
// batch's splats (block_hit_lists.glsl), widened to its subgroup's blocks so that a subgroup's
// invocations walk one list together.
//
// Per pixel (PER_SPLAT 0): each invocation replays its own pixel, the subgroup walking its list
// one splat at a time; the subgroup sums its pixels' gradients for the splat (add_subgroup_sum:
// 4 + 2 log2(subgroup size) shuffles) and nine invocations add the nine sums at once (in
// subgroups of 16 or more; smaller ones add the ninth after the eight). Where one pixel alone
// blended the splat, its nine values go to nine invocations the same way (add_lane_gradient).
//
// Per splat (PER_SPLAT 1): the subgroup's invocations hold consecutive splats of its list, back to
// front, and its W pixels' replay state (transmittance, colour behind) lies in shared memory (W:
// the subgroup size). At step s the lane l replays pixel (s - l) mod W through its splat, and at
// step s + 1 lane l + 1, holding the next splat to the front, takes that pixel on: every pixel
// meets its splats one step after another in back-to-front order, the per-pixel replay exactly
// (the same floats per pixel; only the order of the sums differs), while each splat's gradient
// gathers in its lane's registers over the W pixels. A lane that has met all W pixels takes the
// splat W places further to the front, so the subgroup is full but for W - 1 steps of filling per
// batch, and the finished gradients are added every W steps by all lanes at once.
//
// Why this form: the per-pixel one spends, per splat and subgroup, its sums' shuffles (14 at
// W = 32, each with its selects and add, against ~50 instructions of replay) and atomics; this
// one spends one shared-memory read and write of a pixel's state per step and 9 atomic
// instructions per W splats, and needs no workgroup barrier between steps (the state only moves
// within the subgroup). That pays where lists are long and splats cover the subgroup's pixels:
// large splats, many per tile, which is where a big GPU's backward time goes. The wavefront over
// the whole tile (VkSplat's per-splat backward: a workgroup barrier per step, 511 steps per 256
// splats) and a first pass storing each pixel's state per batch (a second walk of every list)
// both cost more steps than they save on small-subgroup hardware; this one keeps the block lists
// and only adds the filling. Where a block's lists are short, the W - 1 filling steps per batch
// dominate and the per-pixel form wins. Which is faster depends on the GPU and the scene, so
// DifferentiableRenderer times both on the first training steps and keeps the faster.
//
// Neither form assumes a subgroup size (lavapipe runs 4 or 8, AMD 64): both only need full
// subgroups of consecutive invocations, as block_hit_lists.glsl does.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#if FLOAT_ATOMICS
#extension GL_EXT_shader_atomic_float : require
#endif

#include "shaders/common/buffers.h"
#include "vksplat/constants.hpp"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/render/tile_blocks.glsl"
#include "shaders/train/parameter_layout.h"

layout(local_size_x = 256) in;
const uint BATCH = 256;
#include "shaders/render/block_hit_lists.glsl"


void add_gradient(uint index, float value) {
    if (value == 0.0) return;
#if FIXED_POINT_SUMS
    // An integer holds no NaN nor infinity, and a conversion out of its range is undefined: the
    // step is marked instead (parameter_layout.h), and nothing steps.
    if (!(abs(value) < SPLAT_GRAD_FIXED_LIMIT)) {
        atomicOr(pc.status.v[0], STEP_NONFINITE | STEP_NONFINITE_SUMS);
        return;
    }
    atomicAdd(Int64s(pc.splat_grads).v[index], int64_t(round(value * SPLAT_GRAD_FIXED_SCALE)));
#elif FLOAT_ATOMICS
    atomicAdd(pc.splat_grads.v[index], value);
#else
    Uints bits = Uints(pc.splat_grads);
    uint seen = bits.v[index];
    for (;;) {
        const uint before = atomicCompSwap(bits.v[index], seen, floatBitsToUint(uintBitsToFloat(seen) + value));
        if (before == seen) break;
        seen = before;
    }
#endif
}

// A splat's gradient, summed over pixels: d/d 2D mean, conic, opacity and colour.
struct SplatGradient {
    vec2 mean;
    vec3 conic;
    float opacity;
    vec3 color;
};
const SplatGradient NO_GRADIENT = SplatGradient(vec2(0.0), vec3(0.0), 0.0, vec3(0.0));

void add_splat_gradient(uint gaussian, SplatGradient grad) {
    const uint base = gaussian * SPLAT_GRAD_STRIDE;
    add_gradient(base + SPLAT_GRAD_MEAN, grad.mean.x);
    add_gradient(base + SPLAT_GRAD_MEAN + 1u, grad.mean.y);
    add_gradient(base + SPLAT_GRAD_CONIC, grad.conic.x);
    add_gradient(base + SPLAT_GRAD_CONIC + 1u, grad.conic.y);
    add_gradient(base + SPLAT_GRAD_CONIC + 2u, grad.conic.z);
    add_gradient(base + SPLAT_GRAD_OPACITY, grad.opacity);
    add_gradient(base + SPLAT_GRAD_COLOR, grad.color.r);
    add_gradient(base + SPLAT_GRAD_COLOR + 1u, grad.color.g);
    add_gradient(base + SPLAT_GRAD_COLOR + 2u, grad.color.b);
}

#if !PER_SPLAT
// Sums the subgroup's gradients for one splat and adds the totals, the lanes sharing the work.
// Nine subgroupAdds would cost 9 log2(W) shuffles and leave one lane to issue all nine atomics.
// Instead the first butterfly levels halve the set a lane holds: at level s a lane keeps the half
// of its values its bit s selects and sends the other half to its partner lane ^ s, so eight
// values cost 4 + 2 + 1 shuffles, then one per further level, and eight lanes end with one
// total each to add (slot = 4 b0 + 2 b1 + b2 of its lane's low bits). The ninth value takes a
// subgroupAdd, and lane 8 adds it where there is one. Subgroups have at least 4 lanes
// (gpu::Context refuses smaller ones); with exactly 4 each lane ends with two totals.
void add_subgroup_sum(uint gaussian, SplatGradient grad) {
    float v[8] = float[8](grad.mean.x, grad.mean.y, grad.conic.x, grad.conic.y, grad.conic.z, grad.opacity,
                          grad.color.r, grad.color.g);
    const float last_value = subgroupAdd(grad.color.b);
    const uint lane = gl_SubgroupInvocationID, width = gl_SubgroupSize;
    const uint base = gaussian * SPLAT_GRAD_STRIDE;
    const bool upper1 = (lane & 1u) != 0u;
    for (uint i = 0u; i < 4u; ++i) {
        const float send = upper1 ? v[i] : v[i + 4u];
        v[i] = (upper1 ? v[i + 4u] : v[i]) + subgroupShuffleXor(send, 1u);
    }
    const bool upper2 = (lane & 2u) != 0u;
    for (uint i = 0u; i < 2u; ++i) {
        const float send = upper2 ? v[i] : v[i + 2u];
        v[i] = (upper2 ? v[i + 2u] : v[i]) + subgroupShuffleXor(send, 2u);
    }
    uint slot = (upper1 ? 4u : 0u) + (upper2 ? 2u : 0u);  // v[0] and v[1]: slots slot and slot + 1
    if (width >= 8u) {
        const bool upper4 = (lane & 4u) != 0u;
        const float send = upper4 ? v[0] : v[1];
        v[0] = (upper4 ? v[1] : v[0]) + subgroupShuffleXor(send, 4u);
        slot += upper4 ? 1u : 0u;
        for (uint s = 8u; s < width; s *= 2u) v[0] += subgroupShuffleXor(v[0], s);
        if (width >= 16u) {
            // Lane 8 adds the ninth total beside the slots' eight lanes: one add for all nine,
            // where a lane of its own would add it after them.
            if (lane < 9u)
                add_gradient(lane < 8u ? base + slot : base + SPLAT_GRAD_COLOR + 2u, lane < 8u ? v[0] : last_value);
            return;
        }
        if (lane < 8u) add_gradient(base + slot, v[0]);
    } else {
        add_gradient(base + slot, v[0]);
        add_gradient(base + slot + 1u, v[1]);
    }
    if (lane == width - 1u) add_gradient(base + SPLAT_GRAD_COLOR + 2u, last_value);
}

// Adds the gradient of the one lane that blended the splat. In a subgroup of 16 lanes or more,
// lane k takes its k-th value (9 shuffles) and the nine are added at once: the blending lane
// adding them one after another kept the rest idle for 9 serialised adds.
void add_lane_gradient(bool blended, uint gaussian, SplatGradient grad) {
    const uint lane = gl_SubgroupInvocationID;
    if (gl_SubgroupSize < 16u) {
        if (blended) add_splat_gradient(gaussian, grad);
        return;
    }
    const uint source = subgroupBallotFindLSB(subgroupBallot(blended));
    const float values[9] = float[9](grad.mean.x, grad.mean.y, grad.conic.x, grad.conic.y, grad.conic.z,
                                     grad.opacity, grad.color.r, grad.color.g, grad.color.b);
    float mine = 0.0;
    for (uint k = 0u; k < 9u; ++k) {
        const float value = subgroupShuffle(values[k], source);
        if (lane == k) mine = value;
    }
    // The nine values lie at SPLAT_GRAD_MEAN (0) ... SPLAT_GRAD_COLOR + 2 (8) in this order.
    if (lane < 9u) add_gradient(gaussian * SPLAT_GRAD_STRIDE + lane, mine);
}
#endif

// What a pixel's replay reads from the forward pass and the loss.
struct PixelBackward {
    vec2 pixel;
    vec3 dl_dpixel;
    float final_t;
    float background_grad;  // what the background adds through the final transmittance
    uint last;              // one past the list position of the last splat it blended
};

// Where a pixel's replay stands: the transmittance in front of the splat replayed last (before
// the first, the final transmittance) and the colour blended behind that splat, per unit of it.
struct Replay {
    float t;
    vec3 behind;
};

// Replays one splat the pixel blended (its list position below pixel.last): steps `replay` to the
// front of it and gives the derivatives of the pixel's loss as `grad`. The one formula of both forms.
// False where the blend skipped the splat at this pixel (alpha < 1/255): `grad` is zero then.
bool replay_splat(vec2 mean, vec4 conic_o, vec3 color, PixelBackward pixel, inout Replay replay,
                  out SplatGradient grad) {
    grad = NO_GRADIENT;
    const vec2 d = mean - pixel.pixel;
    const float power = -0.5 * (conic_o.x * d.x * d.x + conic_o.z * d.y * d.y) - conic_o.y * d.x * d.y;
    if (power > 0.0) return false;
    const float g = exp(power);
    const float unclamped = conic_o.w * g;
    const float alpha = min(MAX_ALPHA, unclamped);
    if (alpha < MIN_ALPHA) return false;
    replay.t /= 1.0 - alpha;
    grad.color = alpha * replay.t * pixel.dl_dpixel;
    const float dl_dalpha =
        dot(color - replay.behind, pixel.dl_dpixel) * replay.t - pixel.final_t / (1.0 - alpha) * pixel.background_grad;
    replay.behind = alpha * color + (1.0 - alpha) * replay.behind;
    if (unclamped >= MAX_ALPHA) return true;
    grad.opacity = g * dl_dalpha;
    const float dl_dpower = conic_o.w * g * dl_dalpha;
    grad.mean = dl_dpower * vec2(-conic_o.x * d.x - conic_o.y * d.y, -conic_o.y * d.x - conic_o.z * d.y);
    grad.conic = dl_dpower * vec3(-0.5 * d.x * d.x, -d.x * d.y, -0.5 * d.y * d.y);
    return true;
}

#if PER_SPLAT
shared vec2 batch_mean[BATCH];  // with the pixels' state below, the whole fits lavapipe's 32 KiB
#else
shared vec4 batch_mean[BATCH];  // xy: as in blend_body.glsl
#endif
shared vec4 batch_conic_opacity[BATCH];
shared vec4 batch_color[BATCH];
shared uint batch_gaussian[BATCH];
shared uint tile_end;

#if PER_SPLAT
// Per pixel, at its invocation's gl_LocalInvocationIndex: what replay_splat reads, and its Replay.
shared vec4 pixel_grad[BATCH];    // rgb: dL/d rgb, a: final transmittance
shared uint pixel_last[BATCH];
shared vec4 pixel_replay[BATCH];  // x: t, yzw: behind

// The batch's splats of the subgroup's list, per splat (see the top). `walked_end`: the end of the
// list positions any of the subgroup's pixels blended (subgroup-uniform).
void replay_batch_per_splat(uint batch_start, uint my_block, uint walked_end, uvec2 tile_origin, vec3 background) {
    const uint width = gl_SubgroupSize, lane = gl_SubgroupInvocationID;
    // A subgroup's invocations are consecutive (as block_hit_lists.glsl's subgroup_blocks assumes):
    // its q-th pixel is that of invocation first + q.
    const uint first = gl_LocalInvocationIndex - lane;
    const uint list = my_block * BATCH;
    // The list is in list order: only its first `count` splats were blended by any pixel here.
    uint count = 0u;
    for (uint high = block_hit_count[my_block]; count < high;) {
        const uint middle = (count + high) / 2u;
        if (batch_start + block_hits[list + middle] < walked_end) count = middle + 1u;
        else high = middle;
    }
    if (count == 0u) return;
    // The lane's splat: the m-th from the back, m = lane, lane + width, ...
    uint position = 0u, gaussian = 0u;
    vec2 mean = vec2(0.0);
    vec4 conic_o = vec4(0.0);
    vec3 color = vec3(0.0);
    SplatGradient grad = NO_GRADIENT;
    // A splat that has met all the pixels waits with its gradient for the subgroup's next flush
    // (every width steps), so that the lanes add theirs with the same instructions.
    SplatGradient finished = NO_GRADIENT;
    uint finished_gaussian = 0u;
    bool waiting = false;
    for (uint step = 0u; step + 1u < count + width; ++step) {
        if (step >= lane) {
            const uint q = (step - lane) % width;  // the pixel: the q-th of the subgroup
            const uint m = step - q;               // = (step - lane - q) + lane: a multiple of width, plus lane
            if (m < count) {
                if (q == 0u) {
                    const uint j = block_hits[list + count - 1u - m];
                    position = batch_start + j;
                    gaussian = batch_gaussian[j];
                    mean = batch_mean[j];
                    conic_o = batch_conic_opacity[j];
                    color = batch_color[j].rgb;
                    grad = NO_GRADIENT;
                }
                const uint at = first + q;
                const uint last = pixel_last[at];
                if (position < last) {
                    const vec4 dl_final = pixel_grad[at];
                    const PixelBackward pixel = PixelBackward(vec2(tile_origin + pixel_in_tile(at)), dl_final.rgb,
                                                              dl_final.a, dot(background, dl_final.rgb), last);
                    const vec4 state = pixel_replay[at];
                    Replay replay = Replay(state.x, state.yzw);
                    SplatGradient here;
                    replay_splat(mean, conic_o, color, pixel, replay, here);
                    pixel_replay[at] = vec4(replay.t, replay.behind);
                    grad.mean += here.mean;
                    grad.conic += here.conic;
                    grad.opacity += here.opacity;
                    grad.color += here.color;
                }
                if (q == width - 1u) {
                    finished = grad;
                    finished_gaussian = gaussian;
                    waiting = true;
                }
            }
        }
        // A lane finishes a splat every width steps, so no splat waits past the next flush.
        if (step % width == width - 1u || step + 2u == count + width) {
            if (waiting) add_splat_gradient(finished_gaussian, finished);
            waiting = false;
        }
        // The next lane reads what this step wrote.
        subgroupMemoryBarrierShared();
        subgroupBarrier();
    }
}
#endif

void main() {
    const CameraParams cam = pc.camera.c;
    const uvec2 tile_origin = gl_WorkGroupID.xy * uvec2(TILE_WIDTH, TILE_HEIGHT);
    const uvec2 pixel = tile_origin + pixel_in_tile(gl_LocalInvocationIndex);
    const uint my_block = block_of(gl_LocalInvocationIndex);
    const uint slot = batch_slot();
    const bool inside = pixel.x < cam.size.x && pixel.y < cam.size.y;
    const uvec2 range = pc.ranges.v[gl_WorkGroupID.y * cam.size.z + gl_WorkGroupID.x];

    const uint index = pixel.y * cam.size.x + pixel.x;
    const vec3 dl_dpixel = inside ? pc.pixel_grad.v[index].rgb : vec3(0.0);
    const PixelBackward me = PixelBackward(vec2(pixel), dl_dpixel, inside ? pc.transmittance.v[index] : 0.0,
                                           dot(cam.background.rgb, dl_dpixel), inside ? pc.last.v[index] : 0u);
#if PER_SPLAT
    pixel_grad[gl_LocalInvocationIndex] = vec4(me.dl_dpixel, me.final_t);
    pixel_last[gl_LocalInvocationIndex] = me.last;
    pixel_replay[gl_LocalInvocationIndex] = vec4(me.final_t, vec3(0.0));
    const uint walked_end = subgroupMax(me.last);
#else
    Replay replay = Replay(me.final_t, vec3(0.0));
#endif

    if (gl_LocalInvocationIndex == 0u) tile_end = range.x;
    barrier();
    if (me.last > range.x) atomicMax(tile_end, me.last);
    barrier();
    const uint end = min(tile_end, range.y);

    for (uint batch_end = end; batch_end > range.x;) {
        const uint batch_size = min(BATCH, batch_end - range.x);
        const uint batch_start = batch_end - batch_size;
        barrier();  // the previous batch is done with shared memory
        uint touched = 0u;
        if (slot < batch_size) {
            const uint g = pc.tile_values.v[batch_start + slot];
            const Footprint footprint = pc.footprints.v[g];
            const vec2 mean = footprint_mean(footprint);
            const vec4 conic_o = footprint_conic_opacity(footprint);
            batch_gaussian[slot] = g;
#if PER_SPLAT
            batch_mean[slot] = mean;
#else
            batch_mean[slot] = vec4(mean, 0.0, 0.0);
#endif
            batch_conic_opacity[slot] = conic_o;
            batch_color[slot] = pc.colors.v[g];
            touched = subgroup_blocks(touched_blocks(mean, conic_o, tile_origin));
        }
        list_block_hits(slot, touched);  // its barriers also order the stores above before the walk

#if PER_SPLAT
        replay_batch_per_splat(batch_start, my_block, walked_end, tile_origin, cam.background.rgb);
#else
        const uint hits = block_hit_count[my_block];
        for (uint k = hits; k-- > 0u;) {
            const uint j = block_hits[my_block * BATCH + k];
            const bool walked = batch_start + j < me.last;
            // Whole subgroups skip splats none of their pixels blended (most, for small splats).
            if (!subgroupAny(walked)) continue;
            SplatGradient grad = NO_GRADIENT;
            const bool blended =
                walked && replay_splat(batch_mean[j].xy, batch_conic_opacity[j], batch_color[j].rgb, me, replay, grad);
            // Nor do they reduce gradients that are zero on every lane: the splat's ellipse missed
            // their pixels, or was too faint there, though its bounds touched their block. Where
            // one lane blended it, that lane's gradient is the sum: it adds it without reductions.
            const uint blending = subgroupBallotBitCount(subgroupBallot(blended));
            if (blending == 0u) continue;
            if (blending == 1u) {
                add_lane_gradient(blended, batch_gaussian[j], grad);
                continue;
            }
            add_subgroup_sum(batch_gaussian[j], grad);
        }
#endif
        batch_end = batch_start;
    }
}
