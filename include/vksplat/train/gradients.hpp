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

// Throws std::invalid_argument if weights is not 3 per pixel or the cloud needs sanitising (its
// gradient would not line up with it); InputError for an invalid camera.
RenderGradients render_gradients(const gpu::Context& context, const GaussianCloud& cloud, const Camera& camera,
                                 const RenderSettings& settings, const std::vector<float>& weights,
                                 GradientSums sums = GradientSums::device_default);

}  // namespace vksplat::train
