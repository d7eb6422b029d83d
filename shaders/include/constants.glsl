// The reference rasterizer's constants (Kerbl et al. 2023, graphdeco-inria
// diff-gaussian-rasterization, forward pass). This is the one place the shaders take them from;
// include/vksplat/constants.hpp is its C++ twin and tests/constants_test.cpp checks they agree.
#ifndef VKSPLAT_CONSTANTS_GLSL
#define VKSPLAT_CONSTANTS_GLSL

const uint  TILE_WIDTH = 16;               // BLOCK_X
const uint  TILE_HEIGHT = 16;              // BLOCK_Y
const float NEAR_PLANE = 0.2;              // in_frustum(): p_view.z <= 0.2 is culled
const float JACOBIAN_CLAMP = 1.3;          // limx = 1.3 * tan(fovx / 2)
const float LOW_PASS_FILTER = 0.3;         // added to the 2D covariance's diagonal, in px^2
const float EIGENVALUE_FLOOR = 0.1;        // lambda = mid +- sqrt(max(0.1, mid^2 - det))
const float RADIUS_SIGMAS = 3.0;           // radius = ceil(3 * sqrt(lambda_max))
const float MAX_ALPHA = 0.99;              // alpha = min(0.99, opacity * exp(power))
const float MIN_ALPHA = 1.0 / 255.0;       // contributions with alpha < 1/255 are skipped
const float MIN_TRANSMITTANCE = 0.0001;    // stop before T would fall below 1e-4
const float COLOR_OFFSET = 0.5;            // colour = SH + 0.5, clamped at 0

#endif
