// The reference rasterizer's constants (Kerbl et al. 2023, graphdeco-inria
// diff-gaussian-rasterization, forward pass): the one place both the shaders and C++ take them
// from. glslang compiles this header too (shaders include "vksplat/constants.hpp"), where each
// constant is a GLSL `const` under its GLSL name; C++ sees vksplat::constants::k<Name>.
#ifndef VKSPLAT_CONSTANTS_HPP
#define VKSPLAT_CONSTANTS_HPP

#ifdef __cplusplus
#include <cstdint>
#define VKSPLAT_UINT_CONSTANT(glsl_name, cpp_name, value) inline constexpr std::uint32_t cpp_name = value;
#define VKSPLAT_FLOAT_CONSTANT(glsl_name, cpp_name, value) inline constexpr float cpp_name = value;
namespace vksplat::constants {
#else
#define VKSPLAT_UINT_CONSTANT(glsl_name, cpp_name, value) const uint glsl_name = value;
#define VKSPLAT_FLOAT_CONSTANT(glsl_name, cpp_name, value) const float glsl_name = value;
#endif

VKSPLAT_UINT_CONSTANT(TILE_WIDTH, kTileWidth, 16)                         // BLOCK_X
VKSPLAT_UINT_CONSTANT(TILE_HEIGHT, kTileHeight, 16)                       // BLOCK_Y
VKSPLAT_FLOAT_CONSTANT(NEAR_PLANE, kNearPlane, 0.2f)                      // in_frustum(): p_view.z <= 0.2 is culled
VKSPLAT_FLOAT_CONSTANT(JACOBIAN_CLAMP, kJacobianClamp, 1.3f)              // limx = 1.3 * tan(fovx / 2)
VKSPLAT_FLOAT_CONSTANT(LOW_PASS_FILTER, kLowPassFilter, 0.3f)             // added to the 2D covariance's diagonal, in px^2
VKSPLAT_FLOAT_CONSTANT(EIGENVALUE_FLOOR, kEigenvalueFloor, 0.1f)          // lambda = mid +- sqrt(max(0.1, mid^2 - det))
VKSPLAT_FLOAT_CONSTANT(RADIUS_SIGMAS, kRadiusSigmas, 3.0f)                // radius = ceil(3 * sqrt(lambda_max))
VKSPLAT_FLOAT_CONSTANT(MAX_ALPHA, kMaxAlpha, 0.99f)                       // alpha = min(0.99, opacity * exp(power))
VKSPLAT_FLOAT_CONSTANT(MIN_ALPHA, kMinAlpha, 1.0f / 255.0f)               // contributions with alpha < 1/255 are skipped
VKSPLAT_FLOAT_CONSTANT(MIN_TRANSMITTANCE, kMinTransmittance, 0.0001f)     // stop before T would fall below 1e-4
VKSPLAT_FLOAT_CONSTANT(COLOR_OFFSET, kColorOffset, 0.5f)                  // colour = SH + 0.5, clamped at 0

#undef VKSPLAT_UINT_CONSTANT
#undef VKSPLAT_FLOAT_CONSTANT
#ifdef __cplusplus
}  // namespace vksplat::constants
#endif

#endif
