#version 460
// Training loss and its gradient in one pass: per pixel and channel the SSIM map s from the
// Gaussian-window moments of x (rendered) and y (photo), the L1 and squared-error terms, the
// per-workgroup sums of all three (the host adds the workgroups' sums in double), and dL/dx.
//
// With mu_x = G*x, sigma_xy = G*(xy) - mu_x mu_y (G the 11 x 11 window, zero padding) and
//   s = a b / (c d),  a = 2 mu_x mu_y + C1,  b = 2 sigma_xy + C2,
//                     c = mu_x^2 + mu_y^2 + C1,  d = sigma_x^2 + sigma_y^2 + C2,
// where sigma_x^2 + sigma_y^2 = G*(x^2 + y^2) - mu_x^2 - mu_y^2 (one moment fewer to filter than
// the two variances apart), s depends on x only through G*x, G*(x^2 + y^2) and G*(xy). Its partial
// derivatives with respect to them, each scaled by w = -lambda * mask / (3WH) (the SSIM part of
// dL/ds), are the planes
//   A = w ds/d(G*x)          = w (ds/dmu_x - 2 mu_x ds/dd - mu_y ds/dsigma_xy)
//   B = w ds/d(G*(x^2+y^2))  = w ds/dd          = -w s / d
//   C = w ds/d(G*(xy))       = w ds/dsigma_xy   = w 2a / (c d)
// with ds/dmu_x = 2b / (c d) (mu_y - mu_x a / c) (holding d and sigma_xy fixed). Masking the map
// before differentiating is what lets a masked pixel still pass gradient to the SSIM of unmasked
// neighbours. Pixel q's x enters the filtered moments of every pixel p in its window, as
// G(p - q) x_q in G*x, G(p - q) x_q^2 in G*(x^2 + y^2) and G(p - q) x_q y_q in G*(xy), so
//   dL/dx_q = sum_p G(p - q) (A_p + 2 x_q B_p + y_q C_p) + (1 - lambda) mask_q sign(x_q - y_q) / (3WH)
//           = (G*A)_q + 2 x_q (G*B)_q + y_q (G*C)_q + the L1 term.
// The window is symmetric, and the sum runs over the image's pixels p only, so the adjoint of the
// zero-padded filter is the same filter over planes that are 0 outside the image.
//
// A workgroup owns a 16 x 16 tile of pixels (grid-stride over tiles). The gradient of the tile
// needs A, B, C over the tile plus 5 pixels each side (the region, 26 x 26), and those need x and
// y over 5 more (the input, 36 x 36). The workgroup computes them all itself, channel by channel,
// in shared memory, so no per-pixel map leaves the chip and there is one dispatch: the region's
// moments are recomputed by the neighbouring tiles too, which costs arithmetic but saves writing
// and reading back 9 floats per pixel and a device-wide barrier. Each filter is separable (11 taps
// along columns, then rows) and each invocation computes a run of RUN outputs from RUN + 10 inputs
// held in registers, so shared memory is read about 3.5 times per output instead of 11. The
// shared array (15 KiB) fits the 16 KiB every Vulkan device offers.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "shaders/train/loss.h"
layout(push_constant) uniform Push { LossPush pc; };

const uint TILE = LOSS_TILE;                  // pixels per tile side = workgroup side
const int RADIUS = 5;                         // window 11 x 11
const uint TAPS = 2 * RADIUS + 1;
const uint REGION = TILE + 2 * RADIUS;        // pixels per side whose SSIM terms reach the tile
const uint INPUT = REGION + 2 * RADIUS;       // pixels per side whose values reach the region
const uint INVOCATIONS = TILE * TILE;
const uint RUN = 4;                           // outputs per invocation of a filter
const uint RUN_INPUTS = RUN + TAPS - 1;       // the inputs those outputs read
const uint REGION_RUNS = (REGION + RUN - 1) / RUN;  // runs per region line (the last one partly used)
const uint TILE_RUNS = TILE / RUN;

// The three filters and who runs them: invocation t < *_FILTERS runs line t % lines, run t / lines.
const uint MOMENT_COLUMNS = INPUT * REGION_RUNS;   // G along columns of x, y, x^2 + y^2, xy: INPUT columns
const uint MOMENT_ROWS = REGION * REGION_RUNS;     // then along the REGION rows: the region's moments, A, B, C
const uint PLANE_ROWS = REGION * TILE_RUNS;        // G of A, B, C along the region's rows, tile columns only
// (the last filter, along the tile's columns, is one output pixel per invocation)

// One shared array, reused by the phases of a channel; lines padded by one float so that
// invocations walking neighbouring lines hit different banks.
const uint MOMENT_PITCH = INPUT + 1;
const uint MOMENT_PLANE = REGION * MOMENT_PITCH;   // 4 planes: column-filtered moments, REGION x INPUT
const uint ABC_PITCH = REGION + 1;
const uint ABC_PLANE = REGION * ABC_PITCH;         // 3 planes: A, B, C over the region
const uint FILTERED_OFFSET = 3 * ABC_PLANE;        // then 3 planes of the same along rows, REGION x TILE
const uint FILTERED_PLANE = REGION * TILE;
const uint SCRATCH = 4 * MOMENT_PLANE;
shared float scratch[SCRATCH];
// A compile-time check (glslang rejects an array of size 0): each filter has an invocation per
// run, and the filtered planes and the final sums fit beside what they must not overwrite.
shared float layout_fits[uint(MOMENT_COLUMNS <= INVOCATIONS && MOMENT_ROWS <= INVOCATIONS &&
                              PLANE_ROWS <= INVOCATIONS && FILTERED_OFFSET + 3 * FILTERED_PLANE <= SCRATCH &&
                              3 * INVOCATIONS <= SCRATCH)];

layout(local_size_x = TILE, local_size_y = TILE) in;

// The normalised 1D Gaussian of sigma 1.5 over -5..5 (computed in double, rounded to float). The
// 2D window is its outer product, so the filter is separable.
const float WINDOW[TAPS] = float[](1.028380084e-03, 7.598758135e-03, 3.600077213e-02, 1.093606895e-01,
                                   2.130055377e-01, 2.660117249e-01, 2.130055377e-01, 1.093606895e-01,
                                   3.600077213e-02, 7.598758135e-03, 1.028380084e-03);
const float SSIM_C1 = 0.01 * 0.01;
const float SSIM_C2 = 0.03 * 0.03;

bool inside(ivec2 pixel) {
    return all(greaterThanEqual(pixel, ivec2(0))) && pixel.x < int(pc.width) && pixel.y < int(pc.height);
}

uint pixel_index(ivec2 pixel) { return uint(pixel.y) * pc.width + uint(pixel.x); }

// A photo channel as a float. Multiplying by the float 1/255 (rather than dividing) is exactly
// rounded on every device, so the host can form bit-identical values (the tests rely on it).
float photo_channel(uint word, uint channel) { return float((word >> (8u * channel)) & 255u) * (1.0 / 255.0); }

float photo_mask(uint word) { return (word >> 24u) != 0u ? 1.0 : 0.0; }

void main() {
    const uvec2 local = gl_LocalInvocationID.xy;
    const uint thread = gl_LocalInvocationIndex;
    const float l1_weight = (1.0 - pc.ssim_weight) * pc.inv_count;
    float l1_sum = 0.0, ssim_sum = 0.0, mse_sum = 0.0;

    // This invocation's line and run in each filter.
    const uint column = thread % INPUT, column_run = thread / INPUT;
    const uint moment_row = thread % REGION, moment_run = thread / REGION;
    const uint plane_row = thread % REGION, plane_run = thread / REGION;

    for (uint tile = gl_WorkGroupID.x; tile < pc.tiles; tile += gl_NumWorkGroups.x) {
        const ivec2 origin = ivec2(tile % pc.tiles_x, tile / pc.tiles_x) * int(TILE);
        const ivec2 region_origin = origin - RADIUS, input_origin = origin - 2 * RADIUS;

        // Everything the tile reads from memory, in one batch before any filtering, so that the
        // loads' latency is paid once per tile. Pixels outside the image read as 0 (the zero
        // padding of the reference's F.conv2d(padding = 5)).
        // The column filter's inputs: column `column` of the input, rows column_run * RUN onwards.
        vec3 run_x[RUN_INPUTS];
        uint run_photo[RUN_INPUTS];
        [[unroll]] for (uint k = 0u; k < RUN_INPUTS; ++k) {
            const uint row = column_run * RUN + k;
            const ivec2 p = input_origin + ivec2(column, row);
            run_x[k] = vec3(0.0);
            run_photo[k] = 0u;  // reads as 0 in every channel
            if (thread < MOMENT_COLUMNS && row < INPUT && inside(p)) {
                const uint j = pixel_index(p);
                run_x[k] = pc.rendered.v[j].rgb;
                run_photo[k] = pc.photo.v[j];
            }
        }
        // The masks of the region pixels whose SSIM this invocation evaluates; 0 outside the
        // image, where s has no term, so that A, B, C are 0 there.
        float run_mask[RUN];
        [[unroll]] for (uint i = 0u; i < RUN; ++i) {
            const ivec2 p = region_origin + ivec2(moment_run * RUN + i, moment_row);
            run_mask[i] = thread < MOMENT_ROWS && inside(p) ? photo_mask(pc.photo.v[pixel_index(p)]) : 0.0;
        }
        // This invocation's own pixel, whose gradient it writes.
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
        const vec3 diff = x - y;
        l1_sum += mask * (abs(diff.r) + abs(diff.g) + abs(diff.b));
        mse_sum += mask * dot(diff, diff);

        [[unroll]] for (uint ch = 0u; ch < 3u; ++ch) {
            // G along columns of x, y, x^2 + y^2 and xy: a run of rows of one input column.
            if (thread < MOMENT_COLUMNS) {
                vec4 products[RUN_INPUTS];
                [[unroll]] for (uint k = 0u; k < RUN_INPUTS; ++k) {
                    const vec2 v = vec2(run_x[k][ch], photo_channel(run_photo[k], ch));
                    products[k] = vec4(v, dot(v, v), v.x * v.y);
                }
                [[unroll]] for (uint i = 0u; i < RUN; ++i) {
                    const uint row = column_run * RUN + i;
                    if (row < REGION) {
                        vec4 sum = vec4(0.0);
                        [[unroll]] for (uint k = 0u; k < TAPS; ++k) sum += WINDOW[k] * products[i + k];
                        [[unroll]] for (uint m = 0u; m < 4u; ++m)
                            scratch[m * MOMENT_PLANE + row * MOMENT_PITCH + column] = sum[m];
                    }
                }
            }
            barrier();
            // Then along rows: the region's moments, its SSIM terms and A, B, C.
            vec3 abc[RUN];
            if (thread < MOMENT_ROWS) {
                vec4 columns[RUN_INPUTS];
                [[unroll]] for (uint k = 0u; k < RUN_INPUTS; ++k) {
                    const uint col = moment_run * RUN + k;
                    columns[k] = vec4(0.0);
                    if (col < INPUT) {
                        const uint at = moment_row * MOMENT_PITCH + col;
                        columns[k] = vec4(scratch[at], scratch[at + MOMENT_PLANE], scratch[at + 2u * MOMENT_PLANE],
                                           scratch[at + 3u * MOMENT_PLANE]);
                    }
                }
                [[unroll]] for (uint i = 0u; i < RUN; ++i) {
                    const uvec2 at = uvec2(moment_run * RUN + i, moment_row);
                    if (at.x >= REGION) break;  // the last run's tail
                    vec4 moments = vec4(0.0);
                    [[unroll]] for (uint k = 0u; k < TAPS; ++k) moments += WINDOW[k] * columns[i + k];
                    const float mu_x = moments.x, mu_y = moments.y;
                    const float a = 2.0 * mu_x * mu_y + SSIM_C1, b = 2.0 * (moments.w - mu_x * mu_y) + SSIM_C2;
                    const float c = mu_x * mu_x + mu_y * mu_y + SSIM_C1;
                    const float d = moments.z - mu_x * mu_x - mu_y * mu_y + SSIM_C2;
                    const float inv_cd = 1.0 / (c * d);  // the one division: 1/c = d inv_cd, 1/d = c inv_cd
                    const float s = a * b * inv_cd;
                    const float ds_dd = -s * c * inv_cd;
                    const float ds_dcov = 2.0 * a * inv_cd;
                    const float ds_dmu_x = 2.0 * b * inv_cd * (mu_y - mu_x * a * d * inv_cd);
                    const float w = -pc.ssim_weight * run_mask[i] * pc.inv_count;
                    abc[i] = w * vec3(ds_dmu_x - 2.0 * mu_x * ds_dd - mu_y * ds_dcov, ds_dd, ds_dcov);
                    // The tile's own pixels' terms (the region's others belong to other tiles).
                    if (all(greaterThanEqual(at, uvec2(RADIUS))) && all(lessThan(at, uvec2(RADIUS + TILE))))
                        ssim_sum += run_mask[i] * s;
                }
            }
            barrier();  // every invocation is done reading the moments, which A, B, C overwrite
            if (thread < MOMENT_ROWS) {
                [[unroll]] for (uint i = 0u; i < RUN; ++i) {
                    const uint col = moment_run * RUN + i;
                    if (col < REGION) {
                        const uint at = moment_row * ABC_PITCH + col;
                        scratch[at] = abc[i].x;
                        scratch[at + ABC_PLANE] = abc[i].y;
                        scratch[at + 2u * ABC_PLANE] = abc[i].z;
                    }
                }
            }
            barrier();
            // G of A, B, C along the region's rows, for the tile's columns.
            if (thread < PLANE_ROWS) {
                vec3 planes[RUN_INPUTS];
                [[unroll]] for (uint k = 0u; k < RUN_INPUTS; ++k) {
                    const uint at = plane_row * ABC_PITCH + plane_run * RUN + k;
                    planes[k] = vec3(scratch[at], scratch[at + ABC_PLANE], scratch[at + 2u * ABC_PLANE]);
                }
                [[unroll]] for (uint i = 0u; i < RUN; ++i) {
                    vec3 sum = vec3(0.0);
                    [[unroll]] for (uint k = 0u; k < TAPS; ++k) sum += WINDOW[k] * planes[i + k];
                    const uint at = FILTERED_OFFSET + plane_row * TILE + plane_run * RUN + i;
                    scratch[at] = sum.x;
                    scratch[at + FILTERED_PLANE] = sum.y;
                    scratch[at + 2u * FILTERED_PLANE] = sum.z;
                }
            }
            barrier();
            // Then along the tile's columns, at this invocation's pixel.
            vec3 filtered = vec3(0.0);
            [[unroll]] for (uint k = 0u; k < TAPS; ++k) {
                const uint at = FILTERED_OFFSET + (local.y + k) * TILE + local.x;
                filtered += WINDOW[k] * vec3(scratch[at], scratch[at + FILTERED_PLANE], scratch[at + 2u * FILTERED_PLANE]);
            }
            gradient[ch] += filtered.x + 2.0 * x[ch] * filtered.y + y[ch] * filtered.z;
            barrier();  // every invocation is done reading the filtered planes, which the next channel overwrites
        }
        if (owned) pc.gradient.v[index] = vec4(gradient, 0.0);
    }

    // Workgroup sums by a tree in shared memory: same order on every run and device, and no
    // assumption about the subgroup size. The last barrier of the tile loop ended every read.
    scratch[thread] = l1_sum;
    scratch[thread + INVOCATIONS] = ssim_sum;
    scratch[thread + 2u * INVOCATIONS] = mse_sum;
    barrier();
    for (uint half_size = INVOCATIONS / 2u; half_size > 0u; half_size /= 2u) {
        if (thread < half_size) {
            [[unroll]] for (uint k = 0u; k < 3u; ++k)
                scratch[thread + k * INVOCATIONS] += scratch[thread + half_size + k * INVOCATIONS];
        }
        barrier();
    }
    if (thread == 0u) pc.partials.v[gl_WorkGroupID.x] = vec4(scratch[0], scratch[INVOCATIONS], scratch[2u * INVOCATIONS], 0.0);
}
