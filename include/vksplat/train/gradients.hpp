#pragma once
// The backward pass on its own: the gradient of a linear function of one rendered picture with
// respect to every raw parameter of the scene. What the gradient tests check against finite
// differences of the reference rasterizer, and a way for a caller's own loss (computed on the
// host from the picture) to reach the parameters.
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::train {

struct RenderGradients {
    RenderOutput image;      // rgb and alpha of the frame differentiated (no depth or statistics)
    // dL/d parameter in the cloud's own arrays: positions, log_scales, rotations (of the raw,
    // unnormalised quaternion), opacity_logits and sh, for L = sum over pixels p and channels c
    // of weights[3 p + c] * rgb[3 p + c].
    GaussianCloud gradient;
};

// How the blend backward sums each splat's gradients over pixels: with float atomics where the
// device has them (VK_EXT_shader_atomic_float), else with the compare-and-swap loop every device
// can run; compare_and_swap forces the loop (to test it on any device). Either way the order of
// the float additions varies from run to run, and so do the last bits of the sums. fixed_point
// adds 64-bit integers (2^-40 steps) instead, whose totals do not depend on the order: the same
// gradients, to ~1e-12 absolute, every run (train --deterministic; needs 64-bit buffer atomics).
enum class GradientSums { device_default, compare_and_swap, fixed_point };

// How the blend backward divides its work (shaders/train/blend_backward.glsl): per_pixel, each
// invocation replays one pixel and a subgroup sums a splat's gradients over its pixels; per_splat,
// each invocation holds one splat of its subgroup's list and sums its gradient over the subgroup's
// pixels in registers. The same gradients up to the order of the float additions; which is faster
// depends on the GPU and the scene, so `fastest` times both on the first steps (alternating, the
// median of 10 each) and keeps the faster, timing them again whenever the scene has doubled or
// halved since. fixed_point sums run per pixel only (fastest then means
// per_pixel; per_splat with them is refused), so that --deterministic runs never switch form.
enum class BlendBackward { fastest, per_pixel, per_splat };

// Throws std::invalid_argument if weights is not 3 per pixel or the cloud needs sanitising (its
// gradient would not line up with it), or for per_splat with fixed_point sums; InputError for an
// invalid camera. One frame times nothing: `fastest` runs per pixel here.
RenderGradients render_gradients(const gpu::Context& context, const GaussianCloud& cloud, const Camera& camera,
                                 const RenderSettings& settings, const std::vector<float>& weights,
                                 GradientSums sums = GradientSums::device_default,
                                 BlendBackward form = BlendBackward::fastest);

}  // namespace vksplat::train
