#pragma once
// C++ twin of shaders/include/constants.glsl: the reference rasterizer's constants.
// tests/constants_test.cpp parses the GLSL file and checks every value here against it.
#include <cstdint>

namespace vksplat::constants {

inline constexpr uint32_t kTileWidth = 16;
inline constexpr uint32_t kTileHeight = 16;
inline constexpr float kNearPlane = 0.2f;
inline constexpr float kJacobianClamp = 1.3f;
inline constexpr float kLowPassFilter = 0.3f;
inline constexpr float kEigenvalueFloor = 0.1f;
inline constexpr float kRadiusSigmas = 3.0f;
inline constexpr float kMaxAlpha = 0.99f;
inline constexpr float kMinAlpha = 1.0f / 255.0f;
inline constexpr float kMinTransmittance = 0.0001f;
inline constexpr float kColorOffset = 0.5f;

}  // namespace vksplat::constants
