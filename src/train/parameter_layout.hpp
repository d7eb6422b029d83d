#pragma once
// C++ twin of shaders/include/train_layout.glsl: where each parameter of N Gaussians sits in the
// trainer's one float array (and in its gradients and Adam moments, laid out the same).
#include <cstdint>

namespace vksplat::train {

struct ParameterLayout {
    uint32_t count = 0;            // Gaussians
    uint32_t sh_coefficients = 1;  // per channel: 1, 4, 9 or 16

    uint64_t positions() const { return 0; }
    uint64_t log_scales() const { return 3ull * count; }
    uint64_t rotations() const { return 6ull * count; }
    uint64_t opacities() const { return 10ull * count; }
    uint64_t sh() const { return 11ull * count; }
    uint64_t floats_per_gaussian() const { return 11ull + 3ull * sh_coefficients; }
    uint64_t total() const { return floats_per_gaussian() * count; }
};

constexpr uint32_t kSplatGradStride = 9;  // SPLAT_GRAD_STRIDE
constexpr uint32_t kDensifyStride = 3;    // DENSIFY_STRIDE: gradient norm sum, views, max radius
constexpr uint32_t kStepNonfinite = 1;    // STEP_NONFINITE
constexpr uint32_t kStepOverflowed = 2;   // STEP_OVERFLOWED

}  // namespace vksplat::train
