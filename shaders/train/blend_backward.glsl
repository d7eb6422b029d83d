#if !defined(FLOAT_ATOMICS) || !defined(FIXED_POINT_SUMS)
#error define FLOAT_ATOMICS and FIXED_POINT_SUMS before including blend_backward.glsl
#endif
// The blend's backward pass, included after its push constants `pc` (BlendBackwardPush,
// shaders/train/differentiable_renderer.h) by blend_backward.comp (FLOAT_ATOMICS 1: the device adds
// floats atomically), blend_backward_cas.comp (0: a compare-and-swap loop, for devices without
// VK_EXT_shader_atomic_float; the same sums, slower, and in either case their order varies) and
// blend_backward_fixed.comp (FIXED_POINT_SUMS 1: 64-bit integer sums, the same in any order).
//
// One workgroup per tile, one thread per pixel, the pixels in blend_body.glsl's order. Each pixel
// replays the splats it walked (list positions below its `last`) back to front, recovering the
// transmittance in front of each splat from the final one (T_j = T_{j+1} / (1 - alpha_j)) and
// the colour blended behind it, and so the exact derivative of its colour with respect to each
// splat's colour, opacity, 2D mean and conic. Alpha is recomputed with blend_body's formula, so
// the splats skipped there (alpha < 1/255) are skipped here. Unlike the reference, a splat whose
// alpha was clamped at 0.99 gets no gradient through opacity or shape: the clamp is flat there.
// A subgroup sums its pixels' gradients for a splat, and one invocation adds the sums to the
// splat's totals (shaders/train/parameter_layout.h's SPLAT_GRAD_ slots). Like the blend, a pixel walks only its
// block's list of the batch's splats (block_hit_lists.glsl), widened to its subgroup's blocks so
// that a subgroup's invocations walk one list together.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_vote : require
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

shared vec4 batch_mean[BATCH];  // xy: as in blend_body.glsl
shared vec4 batch_conic_opacity[BATCH];
shared vec4 batch_color[BATCH];
shared uint batch_gaussian[BATCH];
shared uint tile_end;

void main() {
    const CameraParams cam = pc.camera.c;
    const uvec2 tile_origin = gl_WorkGroupID.xy * uvec2(TILE_WIDTH, TILE_HEIGHT);
    const uvec2 pixel = tile_origin + pixel_in_tile(gl_LocalInvocationIndex);
    const uint my_block = block_of(gl_LocalInvocationIndex);
    const uint slot = batch_slot();
    const bool inside = pixel.x < cam.size.x && pixel.y < cam.size.y;
    const vec2 pixel_f = vec2(pixel);
    const uvec2 range = pc.ranges.v[gl_WorkGroupID.y * cam.size.z + gl_WorkGroupID.x];

    const uint index = pixel.y * cam.size.x + pixel.x;
    const float final_t = inside ? pc.transmittance.v[index] : 0.0;
    const uint last = inside ? pc.last.v[index] : 0u;
    const vec3 dl_dpixel = inside ? pc.pixel_grad.v[index].rgb : vec3(0.0);
    // What the background adds through the final transmittance.
    const float background_grad = dot(cam.background.rgb, dl_dpixel);

    if (gl_LocalInvocationIndex == 0u) tile_end = range.x;
    barrier();
    if (last > range.x) atomicMax(tile_end, last);
    barrier();
    const uint end = min(tile_end, range.y);

    float t = final_t;
    vec3 behind = vec3(0.0);  // colour blended behind the current splat, per unit of its transmittance
    vec3 last_color = vec3(0.0);
    float last_alpha = 0.0;

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
            batch_mean[slot] = vec4(mean, 0.0, 0.0);
            batch_conic_opacity[slot] = conic_o;
            batch_color[slot] = pc.colors.v[g];
            touched = subgroup_blocks(touched_blocks(mean, conic_o, tile_origin));
        }
        list_block_hits(slot, touched);  // its barriers also order the stores above before the walk

        const uint hits = block_hit_count[my_block];
        for (uint k = hits; k-- > 0u;) {
            const uint j = block_hits[my_block * BATCH + k];
            const bool walked = batch_start + j < last;
            // Whole subgroups skip splats none of their pixels blended (most, for small splats).
            if (!subgroupAny(walked)) continue;
            vec2 grad_mean = vec2(0.0);
            vec3 grad_conic = vec3(0.0), grad_color = vec3(0.0);
            float grad_opacity = 0.0;
            if (walked) {
                const vec4 conic_o = batch_conic_opacity[j];
                const vec2 d = batch_mean[j].xy - pixel_f;
                const float power = -0.5 * (conic_o.x * d.x * d.x + conic_o.z * d.y * d.y) - conic_o.y * d.x * d.y;
                if (power <= 0.0) {
                    const float g = exp(power);
                    const float unclamped = conic_o.w * g;
                    const float alpha = min(MAX_ALPHA, unclamped);
                    if (alpha >= MIN_ALPHA) {
                        t /= 1.0 - alpha;
                        const vec3 color = batch_color[j].rgb;
                        grad_color = alpha * t * dl_dpixel;
                        behind = last_alpha * last_color + (1.0 - last_alpha) * behind;
                        last_color = color;
                        last_alpha = alpha;
                        const float dl_dalpha =
                            dot(color - behind, dl_dpixel) * t - final_t / (1.0 - alpha) * background_grad;
                        if (unclamped < MAX_ALPHA) {
                            grad_opacity = g * dl_dalpha;
                            const float dl_dpower = conic_o.w * g * dl_dalpha;
                            grad_mean = dl_dpower * vec2(-conic_o.x * d.x - conic_o.y * d.y,
                                                         -conic_o.y * d.x - conic_o.z * d.y);
                            grad_conic = dl_dpower * vec3(-0.5 * d.x * d.x, -d.x * d.y, -0.5 * d.y * d.y);
                        }
                    }
                }
            }
            grad_mean = subgroupAdd(grad_mean);
            grad_conic = subgroupAdd(grad_conic);
            grad_color = subgroupAdd(grad_color);
            grad_opacity = subgroupAdd(grad_opacity);
            if (subgroupElect()) {
                const uint base = batch_gaussian[j] * SPLAT_GRAD_STRIDE;
                add_gradient(base + SPLAT_GRAD_MEAN, grad_mean.x);
                add_gradient(base + SPLAT_GRAD_MEAN + 1u, grad_mean.y);
                add_gradient(base + SPLAT_GRAD_CONIC, grad_conic.x);
                add_gradient(base + SPLAT_GRAD_CONIC + 1u, grad_conic.y);
                add_gradient(base + SPLAT_GRAD_CONIC + 2u, grad_conic.z);
                add_gradient(base + SPLAT_GRAD_OPACITY, grad_opacity);
                add_gradient(base + SPLAT_GRAD_COLOR, grad_color.r);
                add_gradient(base + SPLAT_GRAD_COLOR + 1u, grad_color.g);
                add_gradient(base + SPLAT_GRAD_COLOR + 2u, grad_color.b);
            }
        }
        batch_end = batch_start;
    }
}
