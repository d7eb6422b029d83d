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
// A workgroup owns one channel of a strip of SEGMENT_TILES tiles of 32 x 8 pixels, one above the
// other, and walks down it (grid-stride over strips x channels). Channels are independent, so
// three workgroups share a strip rather than one walking it three times: a workgroup's bands are
// a chain of barriers, and a 0.4-megapixel photo has only ~225 strips, too few to fill a large GPU
// when each walks 27 bands. The gradient of a tile needs A, B, C
// over the tile's columns plus 5 each side and its rows plus 5 above and below; those need x and y
// over 5 more. The workgroup computes all of it in shared memory, so no per-pixel map leaves the
// chip and the loss is one dispatch. Walking down, each band of rows is filtered once: the filters
// are separable, and the rows a tile shares with the one above (G of A, B, C along rows) stay in a
// ring. Only the columns beside the strip (which the neighbouring strips compute too) and a
// 10-row band at the strip's top are computed twice; wide, short tiles make the columns beside
// fewer for the same shared memory. Each filter invocation computes a run of outputs from inputs
// held in registers, so shared memory is read a few times per output rather than 11. The shared
// array (15 KiB) fits the 16 KiB every Vulkan device offers.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "shaders/train/loss.h"
layout(push_constant) uniform Push { LossPush pc; };

const uint TILE_WIDTH = LOSS_TILE_WIDTH;
const uint TILE_HEIGHT = LOSS_TILE_HEIGHT;     // rows filtered at once, but for the first band
const uint SEGMENT_TILES = LOSS_SEGMENT_TILES;
const int RADIUS = 5;                          // window 11 x 11
const uint TAPS = 2 * RADIUS + 1;
const uint FIRST_BAND = 2 * RADIUS;            // the rows above a strip and its first 5
const uint BAND_ROWS = max(TILE_HEIGHT, FIRST_BAND);
const uint REGION = TILE_WIDTH + 2 * RADIUS;   // columns whose SSIM terms reach the strip
const uint INPUT = REGION + 2 * RADIUS;        // columns whose values reach those
const uint INVOCATIONS = TILE_WIDTH * TILE_HEIGHT;

// The filters of a band and their runs: outputs per invocation, from RUN + TAPS - 1 inputs.
// 1. G along columns of x, y, x^2 + y^2, xy, for the band's rows and the INPUT columns;
const uint MOMENT_RUN = 4;
const uint MOMENT_COLUMNS = INPUT * ((BAND_ROWS + MOMENT_RUN - 1) / MOMENT_RUN);
// 2. then along rows: the moments, SSIM terms and A, B, C of the band's rows, REGION columns;
const uint SSIM_RUN = 2;
const uint SSIM_RUNS = REGION / SSIM_RUN;
const uint SSIM_ROWS = BAND_ROWS * SSIM_RUNS;
// 3. G of A, B, C along rows, for the band's rows and the tile's columns, into the ring;
const uint PLANE_RUN = 2;
const uint PLANE_RUNS = TILE_WIDTH / PLANE_RUN;
const uint PLANE_ROWS = BAND_ROWS * PLANE_RUNS;
// 4. then along columns from the ring: the gradient, one pixel of the tile per invocation.

// Shared memory: the column-filtered moments of a band (4 planes), which A, B, C of the band
// (3 planes) overwrite, and the ring of row-filtered A, B, C (3 planes of RING rows: a tile's rows
// and the 5 each side; the next band overwrites the rows the tile below no longer needs). Lines
// are padded by one float where invocations walk neighbouring lines, so that they hit different
// banks.
const uint MOMENT_PITCH = INPUT + 1;
const uint MOMENT_PLANE = BAND_ROWS * MOMENT_PITCH;
const uint ABC_PITCH = REGION + 1;
const uint ABC_PLANE = BAND_ROWS * ABC_PITCH;
const uint RING = TILE_HEIGHT + 2 * RADIUS;
const uint RING_PLANE = RING * TILE_WIDTH;
const uint RING_OFFSET = 4 * MOMENT_PLANE;
shared float scratch[RING_OFFSET + 3 * RING_PLANE];
// A compile-time check (glslang rejects an array of size 0): each filter has an invocation per
// run, runs tile their lines, A, B, C and the final sums fit where the moments were, and the ring
// holds a band beside the 10 rows before it that the next tile needs.
shared float layout_fits[uint(MOMENT_COLUMNS <= INVOCATIONS && SSIM_ROWS <= INVOCATIONS &&
                              PLANE_ROWS <= INVOCATIONS && REGION % SSIM_RUN == 0 && TILE_WIDTH % PLANE_RUN == 0 &&
                              3 * ABC_PLANE <= RING_OFFSET && 3 * INVOCATIONS <= RING_OFFSET &&
                              2 * RADIUS + TILE_HEIGHT <= RING)];

layout(local_size_x = TILE_WIDTH, local_size_y = TILE_HEIGHT) in;

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

// The ring line of image row y, for a strip whose first row is top.
uint ring_line(int y, int top) { return uint(y - top + RADIUS) % RING; }

void main() {
    const uvec2 local = gl_LocalInvocationID.xy;
    const uint thread = gl_LocalInvocationIndex;
    const float l1_weight = (1.0 - pc.ssim_weight) * pc.inv_count;
    float l1_sum = 0.0, ssim_sum = 0.0, mse_sum = 0.0;

    // This invocation's line and run in each filter: neighbouring invocations take neighbouring
    // columns or runs, so that their shared-memory accesses spread over the banks.
    const uint moment_column = thread % INPUT, moment_run = thread / INPUT;
    const uint ssim_run = thread % SSIM_RUNS, ssim_row = thread / SSIM_RUNS;
    const uint plane_run = thread % PLANE_RUNS, plane_row = thread / PLANE_RUNS;

    for (uint work = gl_WorkGroupID.x; work < 3u * pc.strips; work += gl_NumWorkGroups.x) {
        // The three channels of a strip go to neighbouring workgroups, which read the same lines.
        const uint strip = work / 3u, ch = work % 3u;
        const int left = int(strip % pc.tiles_x * TILE_WIDTH);
        const int top = int(strip / pc.tiles_x * SEGMENT_TILES * TILE_HEIGHT);
        const uint tiles = min(SEGMENT_TILES, pc.tiles_y - strip / pc.tiles_x * SEGMENT_TILES);
        const int bottom = min(top + int(tiles * TILE_HEIGHT), int(pc.height));  // the strip's rows end here

        // Band -1 is rows top - 5 .. top + 4, which the first tile needs from above and
        // beside; band t >= 0 is the rows from 5 below tile t's first to 5 below its last,
        // after which tile t has all it needs.
        for (int band = -1; band < int(tiles); ++band) {
            const int first = band < 0 ? top - RADIUS : top + band * int(TILE_HEIGHT) + RADIUS;
            const uint rows = band < 0 ? FIRST_BAND : TILE_HEIGHT;

            // 1. G along columns of x, y, x^2 + y^2 and xy: a run of rows of one input column.
            // Pixels outside the image read as 0 (the zero padding of the reference's
            // F.conv2d(padding = 5)).
            if (thread < MOMENT_COLUMNS && moment_run * MOMENT_RUN < rows) {
                vec4 products[MOMENT_RUN + TAPS - 1];
                [[unroll]] for (uint k = 0u; k < MOMENT_RUN + TAPS - 1; ++k) {
                    const ivec2 p = ivec2(left - 2 * RADIUS + int(moment_column),
                                          first - RADIUS + int(moment_run * MOMENT_RUN + k));
                    vec2 v = vec2(0.0);
                    if (inside(p)) {
                        const uint j = pixel_index(p);
                        v = vec2(pc.rendered.v[j][ch], photo_channel(pc.photo.v[j], ch));
                    }
                    products[k] = vec4(v, dot(v, v), v.x * v.y);
                }
                [[unroll]] for (uint i = 0u; i < MOMENT_RUN; ++i) {
                    const uint row = moment_run * MOMENT_RUN + i;
                    if (row >= rows) break;  // the last run's tail
                    vec4 sum = vec4(0.0);
                    [[unroll]] for (uint k = 0u; k < TAPS; ++k) sum += WINDOW[k] * products[i + k];
                    const uint at = row * MOMENT_PITCH + moment_column;
                    [[unroll]] for (uint m = 0u; m < 4u; ++m) scratch[at + m * MOMENT_PLANE] = sum[m];
                }
            }
            barrier();
            // 2. Then along rows: the moments, the SSIM terms and A, B, C.
            vec3 abc[SSIM_RUN];
            if (thread < SSIM_ROWS && ssim_row < rows) {
                vec4 columns[SSIM_RUN + TAPS - 1];
                [[unroll]] for (uint k = 0u; k < SSIM_RUN + TAPS - 1; ++k) {
                    const uint at = ssim_row * MOMENT_PITCH + ssim_run * SSIM_RUN + k;
                    columns[k] = vec4(scratch[at], scratch[at + MOMENT_PLANE], scratch[at + 2u * MOMENT_PLANE],
                                      scratch[at + 3u * MOMENT_PLANE]);
                }
                [[unroll]] for (uint i = 0u; i < SSIM_RUN; ++i) {
                    const ivec2 p = ivec2(left - RADIUS + int(ssim_run * SSIM_RUN + i), first + int(ssim_row));
                    // 0 outside the image, where s has no term, so that A, B, C are 0 there.
                    const float mask = inside(p) ? photo_mask(pc.photo.v[pixel_index(p)]) : 0.0;
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
                    const float w = -pc.ssim_weight * mask * pc.inv_count;
                    abc[i] = w * vec3(ds_dmu_x - 2.0 * mu_x * ds_dd - mu_y * ds_dcov, ds_dd, ds_dcov);
                    // The strip's own pixels' terms (the others belong to other strips).
                    if (p.x >= left && p.x < left + int(TILE_WIDTH) && p.y >= top && p.y < bottom)
                        ssim_sum += mask * s;
                }
            }
            barrier();  // every invocation is done reading the moments, which A, B, C overwrite
            if (thread < SSIM_ROWS && ssim_row < rows) {
                [[unroll]] for (uint i = 0u; i < SSIM_RUN; ++i) {
                    const uint at = ssim_row * ABC_PITCH + ssim_run * SSIM_RUN + i;
                    scratch[at] = abc[i].x;
                    scratch[at + ABC_PLANE] = abc[i].y;
                    scratch[at + 2u * ABC_PLANE] = abc[i].z;
                }
            }
            barrier();
            // 3. G of A, B, C along rows, for the tile's columns, into the ring (whose lines
            // the last tile's gradient read before the barriers above).
            if (thread < PLANE_ROWS && plane_row < rows) {
                vec3 planes[PLANE_RUN + TAPS - 1];
                [[unroll]] for (uint k = 0u; k < PLANE_RUN + TAPS - 1; ++k) {
                    const uint at = plane_row * ABC_PITCH + plane_run * PLANE_RUN + k;
                    planes[k] = vec3(scratch[at], scratch[at + ABC_PLANE], scratch[at + 2u * ABC_PLANE]);
                }
                const uint line = RING_OFFSET + ring_line(first + int(plane_row), top) * TILE_WIDTH;
                [[unroll]] for (uint i = 0u; i < PLANE_RUN; ++i) {
                    vec3 sum = vec3(0.0);
                    [[unroll]] for (uint k = 0u; k < TAPS; ++k) sum += WINDOW[k] * planes[i + k];
                    const uint at = line + plane_run * PLANE_RUN + i;
                    scratch[at] = sum.x;
                    scratch[at + RING_PLANE] = sum.y;
                    scratch[at + 2u * RING_PLANE] = sum.z;
                }
            }
            barrier();
            if (band < 0) continue;
            // 4. Tile `band` has its rows: G along columns at this invocation's pixel.
            const ivec2 pixel = ivec2(left, top + band * int(TILE_HEIGHT)) + ivec2(local);
            vec3 filtered = vec3(0.0);
            [[unroll]] for (uint k = 0u; k < TAPS; ++k) {
                const uint at = RING_OFFSET + ring_line(pixel.y - RADIUS + int(k), top) * TILE_WIDTH + local.x;
                filtered += WINDOW[k] * vec3(scratch[at], scratch[at + RING_PLANE], scratch[at + 2u * RING_PLANE]);
            }
            if (inside(pixel)) {
                const uint index = pixel_index(pixel);
                const float x = pc.rendered.v[index][ch];
                const uint word = pc.photo.v[index];
                const float y = photo_channel(word, ch), mask = photo_mask(word);
                // The L1 term; sign(0) = 0, like torch's.
                const float gradient =
                    l1_weight * mask * sign(x - y) + filtered.x + 2.0 * x * filtered.y + y * filtered.z;
                // Each channel's workgroup writes its own float; the first also clears w.
                pc.gradient.v[index][ch] = gradient;
                if (ch == 0u) pc.gradient.v[index].w = 0.0;
                l1_sum += mask * abs(x - y);
                mse_sum += mask * (x - y) * (x - y);
            }
        }
    }

    // Workgroup sums by a tree in shared memory: same order on every run and device, and no
    // assumption about the subgroup size. The last band's barrier ended every read of the
    // moments' and A, B, C's floats, which these overwrite.
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
