// Where a trainable scene's raw parameters (and, in the same layout, their gradients and Adam's
// moments) sit in one float array of N Gaussians with K SH coefficients per channel:
//   positions 3N | log-scales 3N | quaternions (w, x, y, z) 4N | opacity logits N | SH 3KN
// The SH block is [Gaussian][coefficient][rgb], the renderer's own layout, so the renderer's
// preprocess reads the trained SH in place. src/train/parameter_layout.hpp is the C++ twin.
#ifndef VKSPLAT_TRAIN_LAYOUT_GLSL
#define VKSPLAT_TRAIN_LAYOUT_GLSL

uint positions_offset(uint n) { return 0u; }
uint log_scales_offset(uint n) { return 3u * n; }
uint rotations_offset(uint n) { return 6u * n; }
uint opacities_offset(uint n) { return 10u * n; }
uint sh_offset(uint n) { return 11u * n; }

// Per-splat gradients the blend backward accumulates (floats per Gaussian): the projected mean
// (x, y, pixels), the conic (a, b, c), the opacity after the sigmoid and the colour (r, g, b).
const uint SPLAT_GRAD_STRIDE = 9u;
const uint SPLAT_GRAD_MEAN = 0u;
const uint SPLAT_GRAD_CONIC = 2u;
const uint SPLAT_GRAD_OPACITY = 5u;
const uint SPLAT_GRAD_COLOR = 6u;

// What densification decides by, per Gaussian (floats), summed over the steps since the last
// densification: the NDC gradient norm of its projected mean, the views it was drawn in, and the
// largest radius in pixels it had.
const uint DENSIFY_STRIDE = 3u;
const uint DENSIFY_GRAD_SUM = 0u;
const uint DENSIFY_VIEWS = 1u;
const uint DENSIFY_MAX_RADIUS = 2u;

// Bits of the step's status word: why Adam skips this step.
const uint STEP_NONFINITE = 1u;     // some gradient was NaN or infinite
const uint STEP_OVERFLOWED = 2u;    // the view needed more tile entries than the buffers hold

#endif
