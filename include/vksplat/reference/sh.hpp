#pragma once
// Spherical-harmonics colour as the reference rasterizer evaluates it (graphdeco-inria
// diff-gaussian-rasterization, forward.cu computeColorFromSH): the same constants, signs and band
// order, in double precision. shaders/render/sh.glsl is the GPU's copy of the same formula.
#include <array>

#include <glm/glm.hpp>

namespace vksplat::reference {

inline constexpr double kShC0 = 0.28209479177387814;
inline constexpr double kShC1 = 0.4886025119029199;
inline constexpr std::array<double, 5> kShC2{1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                                             -1.0925484305920792, 0.5462742152960396};
inline constexpr std::array<double, 7> kShC3{-0.5900435899266435, 2.890611442640554, -0.4570457994644658,
                                             0.3731763325901154,  -0.4570457994644658, 1.445305721320277,
                                             -0.5900435899266435};

// SH(dir) per colour channel, without the 0.5 offset and without clamping.
// degree: 0..3 (bands used); coeffs: at least (degree + 1)^2 coefficients laid out [coefficient][rgb]
// (GaussianCloud::sh of one Gaussian); dir: unit vector from the camera centre to the Gaussian.
std::array<double, 3> eval_sh(int degree, const float* coeffs, glm::dvec3 dir);

}  // namespace vksplat::reference
