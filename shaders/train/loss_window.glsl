// The training loss's shared parts (loss_forward.comp, loss_backward.comp, which declare their
// push constants `pc`, LossPush of shaders/train/loss.h, before including this): the SSIM window
// and the tiling both passes use.
//
// A workgroup owns a 16 x 16 tile of pixels and walks tiles in a grid-stride loop. To filter the
// tile with the 11 x 11 window it stages the tile plus a 5-pixel apron (26 x 26) of one channel
// in shared memory, filters the rows (26 rows x 16 columns), then the columns (one output pixel
// per invocation). Pixels outside the image read as 0: the zero padding of the reference's
// F.conv2d(padding = 5). One channel at a time keeps shared memory under 16 KiB, the least a
// Vulkan device offers.
#ifndef VKSPLAT_LOSS_WINDOW_GLSL
#define VKSPLAT_LOSS_WINDOW_GLSL

#include "shaders/train/loss.h"

const uint TILE = LOSS_TILE;               // pixels per tile side = workgroup side
const int RADIUS = 5;                      // window 11 x 11
const uint TAPS = 2 * RADIUS + 1;
const uint SPAN = TILE + 2 * RADIUS;       // tile plus apron, per side
const uint STAGED = SPAN * SPAN;           // staged pixels per channel
const uint ROWS_FILTERED = SPAN * TILE;    // results of the row pass
const uint INVOCATIONS = TILE * TILE;
// Staged pixels per invocation. Each invocation loads its share of a tile in one batch, into
// registers, before it fills shared memory channel by channel: the loads' latency is paid once
// per tile rather than once per load.
const uint STAGE_STEPS = (STAGED + INVOCATIONS - 1) / INVOCATIONS;

layout(local_size_x = TILE, local_size_y = TILE) in;

// The normalised 1D Gaussian of sigma 1.5 over -5..5 (computed in double, rounded to float). The
// 2D window is its outer product, so the filter is separable.
const float WINDOW[TAPS] = float[](1.028380084e-03, 7.598758135e-03, 3.600077213e-02, 1.093606895e-01,
                                   2.130055377e-01, 2.660117249e-01, 2.130055377e-01, 1.093606895e-01,
                                   3.600077213e-02, 7.598758135e-03, 1.028380084e-03);
const float SSIM_C1 = 0.01 * 0.01;
const float SSIM_C2 = 0.03 * 0.03;


// The first pixel of a tile.
ivec2 tile_origin(uint tile) { return ivec2(tile % pc.tiles_x, tile / pc.tiles_x) * int(TILE); }

bool inside(ivec2 pixel) {
    return all(greaterThanEqual(pixel, ivec2(0))) && pixel.x < int(pc.width) && pixel.y < int(pc.height);
}

uint pixel_index(ivec2 pixel) { return uint(pixel.y) * pc.width + uint(pixel.x); }

// The image a staged index (0 .. STAGED - 1) of a tile reads from.
ivec2 staged_pixel(ivec2 origin, uint staged) { return origin - RADIUS + ivec2(staged % SPAN, staged / SPAN); }

// A photo channel as a float. Multiplying by the float 1/255 (rather than dividing) is exactly
// rounded on every device, so the host can form bit-identical values (the tests rely on it).
float photo_channel(uint word, uint channel) { return float((word >> (8u * channel)) & 255u) * (1.0 / 255.0); }

float photo_mask(uint word) { return (word >> 24u) != 0u ? 1.0 : 0.0; }

#endif
