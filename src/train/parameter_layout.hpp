#pragma once
// Where each parameter of N Gaussians sits in the trainer's one float array (and in its gradients
// and Adam moments, laid out the same), as shaders/train/parameter_layout.h declares it.
#include <cstdint>

#include "shaders/train/parameter_layout.h"

namespace vksplat::train {

struct ParameterLayout {
    uint32_t count = 0;            // Gaussians
    uint32_t sh_coefficients = 1;  // per channel: 1, 4, 9 or 16

    uint64_t positions() const { return uint64_t(shader::train::kPositionsAt) * count; }
    uint64_t log_scales() const { return uint64_t(shader::train::kLogScalesAt) * count; }
    uint64_t rotations() const { return uint64_t(shader::train::kRotationsAt) * count; }
    uint64_t opacities() const { return uint64_t(shader::train::kOpacitiesAt) * count; }
    uint64_t sh() const { return uint64_t(shader::train::kShAt) * count; }
    uint64_t floats_per_gaussian() const { return shader::train::kShAt + 3ull * sh_coefficients; }
    uint64_t total() const { return floats_per_gaussian() * count; }
};

using shader::train::kDensifyStride;   // gradient norm sum, views, max radius
using shader::train::kSplatGradStride;
using shader::train::kStepNonfinite;
using shader::train::kStepNonfiniteSums;
using shader::train::kStepOverflowed;
using shader::train::kStatusWords;

}  // namespace vksplat::train
