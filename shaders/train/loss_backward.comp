#version 460
// Training loss, backward: dL/dx for every pixel and channel from the planes A, B, C of
// loss_forward.comp. Pixel q's x enters the filtered planes of every pixel p in its window, as
// G(p - q) x_q in G*x, G(p - q) x_q^2 in G*(x^2 + y^2) and G(p - q) x_q y_q in G*(xy), so
//   dL/dx_q = sum_p G(p - q) (A_p + 2 x_q B_p + y_q C_p) + (1 - lambda) mask_q sign(x_q - y_q) / (3WH)
//           = (G*A)_q + 2 x_q (G*B)_q + y_q (G*C)_q + the L1 term.
// The window is symmetric, and the sum runs over the image's pixels p only, so the adjoint of the
// zero-padded filter is the same zero-padded filter: the planes are filtered like the moments.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "shaders/train/loss.h"
layout(push_constant) uniform Push { LossPush pc; };
#include "shaders/train/loss_window.glsl"

// A and B travel as a vec2 and C beside them: vec4 arrays of A, B, C would not fit in 16 KiB.
shared vec2 staged_ab[STAGED];
shared float staged_c[STAGED];
shared vec2 row_ab[ROWS_FILTERED];
shared float row_c[ROWS_FILTERED];

void main() {
    const uvec2 local = gl_LocalInvocationID.xy;
    const uint thread = gl_LocalInvocationIndex;
    const uint pixels = pc.width * pc.height;
    const float l1_weight = (1.0 - pc.ssim_weight) * pc.inv_count;

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
        // The L1 term; sign(0) = 0, like torch's.
        vec3 gradient = l1_weight * mask * sign(x - y);

        // A, B, C of each channel at each staged pixel (0 outside the image).
        vec3 staged[STAGE_STEPS][3];
        [[unroll]] for (uint step = 0u; step < STAGE_STEPS; ++step) {
            const uint i = thread + step * INVOCATIONS;
            const ivec2 p = staged_pixel(origin, i);
            const bool load = i < STAGED && inside(p);
            const uint j = load ? pixel_index(p) : 0u;
            [[unroll]] for (uint ch = 0u; ch < 3u; ++ch) {
                staged[step][ch] = vec3(0.0);
                if (load) {
                    const uint k = 3u * ch * pixels + j;
                    staged[step][ch] = vec3(pc.planes.v[k], pc.planes.v[k + pixels], pc.planes.v[k + 2u * pixels]);
                }
            }
        }

        [[unroll]] for (uint ch = 0u; ch < 3u; ++ch) {
            // As in the forward pass: the staged planes were last read before the row pass's barrier.
            [[unroll]] for (uint step = 0u; step < STAGE_STEPS; ++step) {
                const uint i = thread + step * INVOCATIONS;
                if (i < STAGED) {
                    staged_ab[i] = staged[step][ch].xy;
                    staged_c[i] = staged[step][ch].z;
                }
            }
            barrier();
            for (uint i = thread; i < ROWS_FILTERED; i += INVOCATIONS) {
                const uint first = (i / TILE) * SPAN + i % TILE;
                vec2 ab = vec2(0.0);
                float c = 0.0;
                [[unroll]] for (uint k = 0u; k < TAPS; ++k) {
                    ab += WINDOW[k] * staged_ab[first + k];
                    c += WINDOW[k] * staged_c[first + k];
                }
                row_ab[i] = ab;
                row_c[i] = c;
            }
            barrier();
            vec2 ab = vec2(0.0);
            float c = 0.0;
            [[unroll]] for (uint k = 0u; k < TAPS; ++k) {
                const uint j = (local.y + k) * TILE + local.x;
                ab += WINDOW[k] * row_ab[j];
                c += WINDOW[k] * row_c[j];
            }
            gradient[ch] += ab.x + 2.0 * x[ch] * ab.y + y[ch] * c;
        }
        if (owned) pc.gradient.v[index] = vec4(gradient, 0.0);
    }
}
