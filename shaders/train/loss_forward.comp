#version 460
// Training loss, forward: per pixel and channel the SSIM map s from the Gaussian-window moments
// of x (rendered) and y (photo), the L1 and squared-error terms, and the per-workgroup sums of
// all three (the host adds the workgroups' sums in double). It also writes what the backward pass
// needs, so that pass never recomputes the moments.
//
// With mu_x = G*x, sigma_xy = G*(xy) - mu_x mu_y (G the window) and
//   s = a b / (c d),  a = 2 mu_x mu_y + C1,  b = 2 sigma_xy + C2,
//                     c = mu_x^2 + mu_y^2 + C1,  d = sigma_x^2 + sigma_y^2 + C2,
// where sigma_x^2 + sigma_y^2 = G*(x^2 + y^2) - mu_x^2 - mu_y^2 (one moment fewer to filter than
// the two variances apart), s depends on x only through G*x, G*(x^2 + y^2) and G*(xy). Its partial
// derivatives with respect to them, each scaled by w = -lambda * mask / (3WH) (the SSIM part of
// dL/ds), are the planes
//   A = w ds/d(G*x)          = w (ds/dmu_x - 2 mu_x ds/dd - mu_y ds/dsigma_xy)
//   B = w ds/d(G*(x^2+y^2))  = w ds/dd          = -w s / d
//   C = w ds/d(G*(xy))       = w ds/dsigma_xy   = w 2a / (c d)
// with ds/dmu_x = 2b / (c d) (mu_y - mu_x a / c) (holding d and sigma_xy fixed). Plane k of
// channel ch is planes[(3 ch + k) * width * height + pixel]. Masking the map before differentiating
// is what lets a masked pixel still pass gradient to the SSIM of unmasked neighbours.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "shaders/train/loss.h"
layout(push_constant) uniform Push { LossPush pc; };
#include "shaders/train/loss_window.glsl"

shared vec2 staged_xy[STAGED];
// The row pass's results: G*x, G*y, G*(x^2 + y^2), G*(xy) along rows. After the last tile they
// hold the workgroup's reduction instead (the array is longer than the workgroup).
shared vec4 row_moments[ROWS_FILTERED];

void main() {
    const uvec2 local = gl_LocalInvocationID.xy;
    const uint thread = gl_LocalInvocationIndex;
    const uint pixels = pc.width * pc.height;
    float l1_sum = 0.0, ssim_sum = 0.0, mse_sum = 0.0;

    for (uint tile = gl_WorkGroupID.x; tile < pc.tiles; tile += gl_NumWorkGroups.x) {
        const ivec2 origin = tile_origin(tile);
        const ivec2 pixel = origin + ivec2(local);
        const bool owned = inside(pixel);
        const uint index = owned ? pixel_index(pixel) : 0u;
        vec3 x = vec3(0.0), y = vec3(0.0);
        float mask = 0.0;
        if (owned) {
            x = pc.rendered.v[index].rgb;
            const uint word = pc.photo.v[index];
            y = vec3(photo_channel(word, 0u), photo_channel(word, 1u), photo_channel(word, 2u));
            mask = photo_mask(word);
        }

        vec4 staged_rendered[STAGE_STEPS];
        uint staged_photo[STAGE_STEPS];
        [[unroll]] for (uint step = 0u; step < STAGE_STEPS; ++step) {
            const uint i = thread + step * INVOCATIONS;
            const ivec2 p = staged_pixel(origin, i);
            staged_rendered[step] = vec4(0.0);
            staged_photo[step] = 0u;  // reads as 0 in every channel
            if (i < STAGED && inside(p)) {
                const uint j = pixel_index(p);
                staged_rendered[step] = pc.rendered.v[j];
                staged_photo[step] = pc.photo.v[j];
            }
        }

        [[unroll]] for (uint ch = 0u; ch < 3u; ++ch) {
            // The previous channel's row pass read the staged values before its barrier, so they
            // may be overwritten now; its column pass reads only the row pass's results.
            [[unroll]] for (uint step = 0u; step < STAGE_STEPS; ++step) {
                const uint i = thread + step * INVOCATIONS;
                if (i < STAGED)
                    staged_xy[i] = vec2(staged_rendered[step][ch], photo_channel(staged_photo[step], ch));
            }
            barrier();
            for (uint i = thread; i < ROWS_FILTERED; i += INVOCATIONS) {
                const uint first = (i / TILE) * SPAN + i % TILE;
                vec4 sum = vec4(0.0);
                [[unroll]] for (uint k = 0u; k < TAPS; ++k) {
                    const vec2 v = staged_xy[first + k];
                    sum += WINDOW[k] * vec4(v, dot(v, v), v.x * v.y);
                }
                row_moments[i] = sum;
            }
            barrier();
            vec4 moments = vec4(0.0);
            [[unroll]] for (uint k = 0u; k < TAPS; ++k)
                moments += WINDOW[k] * row_moments[(local.y + k) * TILE + local.x];
            if (owned) {
                const float mu_x = moments.x, mu_y = moments.y;
                const float a = 2.0 * mu_x * mu_y + SSIM_C1, b = 2.0 * (moments.w - mu_x * mu_y) + SSIM_C2;
                const float c = mu_x * mu_x + mu_y * mu_y + SSIM_C1;
                const float d = moments.z - mu_x * mu_x - mu_y * mu_y + SSIM_C2;
                const float s = (a * b) / (c * d);
                const float ds_dd = -s / d;
                const float ds_dcov = 2.0 * a / (c * d);
                const float ds_dmu_x = 2.0 * b / (c * d) * (mu_y - mu_x * a / c);

                const float w = -pc.ssim_weight * mask * pc.inv_count;
                const uint plane = 3u * ch * pixels + index;
                pc.planes.v[plane] = w * (ds_dmu_x - 2.0 * mu_x * ds_dd - mu_y * ds_dcov);
                pc.planes.v[plane + pixels] = w * ds_dd;
                pc.planes.v[plane + 2u * pixels] = w * ds_dcov;

                const float diff = x[ch] - y[ch];
                l1_sum += mask * abs(diff);
                ssim_sum += mask * s;
                mse_sum += mask * diff * diff;
            }
        }
    }

    // Workgroup sums by a tree in shared memory: same order on every run and device, and no
    // assumption about the subgroup size.
    barrier();  // every invocation is done reading the row pass's results
    row_moments[thread] = vec4(l1_sum, ssim_sum, mse_sum, 0.0);
    barrier();
    for (uint half_size = INVOCATIONS / 2u; half_size > 0u; half_size /= 2u) {
        if (thread < half_size) row_moments[thread] += row_moments[thread + half_size];
        barrier();
    }
    if (thread == 0u) pc.partials.v[gl_WorkGroupID.x] = row_moments[0];
}
