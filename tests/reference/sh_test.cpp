// eval_sh against the real spherical harmonics written independently from the textbook formula
//   Y_l^m = sqrt(2) K_l^|m| P_l^|m|(cos theta) {cos(m phi) for m > 0, sin(|m| phi) for m < 0},
//   Y_l^0 = K_l^0 P_l^0(cos theta),  K_l^m = sqrt((2l + 1) / (4 pi) * (l - m)! / (l + m)!),
// with the Condon-Shortley phase in P_l^m, which is where the reference's minus signs come from.
// The reference orders coefficients by band, m = -l..l: index l^2 + l + m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "vksplat/reference/sh.hpp"

namespace vksplat::reference {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Associated Legendre polynomials P_l^m(x), m >= 0, l <= 3, with the Condon-Shortley phase.
double legendre(int l, int m, double x) {
    const double s = std::sqrt(std::max(0.0, 1.0 - x * x));  // sin(theta)
    switch (l * 10 + m) {
        case 0: return 1.0;
        case 10: return x;
        case 11: return -s;
        case 20: return 0.5 * (3.0 * x * x - 1.0);
        case 21: return -3.0 * x * s;
        case 22: return 3.0 * s * s;
        case 30: return 0.5 * (5.0 * x * x * x - 3.0 * x);
        case 31: return -1.5 * (5.0 * x * x - 1.0) * s;
        case 32: return 15.0 * x * s * s;
        case 33: return -15.0 * s * s * s;
    }
    ADD_FAILURE() << "no P_" << l << "^" << m;
    return 0.0;
}

double real_sh(int l, int m, const glm::dvec3& dir) {
    const int am = std::abs(m);
    const double k = std::sqrt((2 * l + 1) / (4.0 * std::numbers::pi) * factorial(l - am) / factorial(l + am));
    const double theta = std::acos(std::clamp(dir.z, -1.0, 1.0)), phi = std::atan2(dir.y, dir.x);
    const double p = legendre(l, am, std::cos(theta));
    if (m == 0) return k * p;
    return std::sqrt(2.0) * k * p * (m > 0 ? std::cos(am * phi) : std::sin(am * phi));
}

std::vector<glm::dvec3> random_directions(int count) {
    std::mt19937 rng(1234);
    std::normal_distribution<double> normal;
    std::vector<glm::dvec3> dirs;
    while (static_cast<int>(dirs.size()) < count) {
        const glm::dvec3 v(normal(rng), normal(rng), normal(rng));
        if (glm::length(v) > 1e-3) dirs.push_back(glm::normalize(v));
    }
    dirs.push_back({0.0, 0.0, 1.0});  // the poles, where phi is arbitrary
    dirs.push_back({0.0, 0.0, -1.0});
    return dirs;
}

TEST(EvalSh, EveryBasisFunctionIsTheRealSphericalHarmonic) {
    for (int l = 0; l <= 3; ++l)
        for (int m = -l; m <= l; ++m) {
            const int index = l * l + l + m;
            // Distinct weights per channel also check the [coefficient][rgb] layout.
            std::vector<float> coeffs(16 * 3, 0.0f);
            coeffs[index * 3 + 0] = 1.0f;
            coeffs[index * 3 + 1] = -2.0f;
            coeffs[index * 3 + 2] = 0.5f;
            for (const glm::dvec3& dir : random_directions(200)) {
                const double expected = real_sh(l, m, dir);
                const std::array<double, 3> rgb = eval_sh(3, coeffs.data(), dir);
                EXPECT_NEAR(rgb[0], expected, 1e-12) << "l=" << l << " m=" << m;
                EXPECT_NEAR(rgb[1], -2.0 * expected, 1e-12) << "l=" << l << " m=" << m;
                EXPECT_NEAR(rgb[2], 0.5 * expected, 1e-12) << "l=" << l << " m=" << m;
            }
        }
}

TEST(EvalSh, DegreeLimitsTheBandsUsed) {
    std::vector<float> coeffs(16 * 3);
    for (size_t i = 0; i < coeffs.size(); ++i) coeffs[i] = 0.1f * static_cast<float>(i % 7) - 0.3f;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    for (int degree = 0; degree <= 3; ++degree) {
        // A higher-degree evaluation with the upper bands zeroed must agree.
        std::vector<float> truncated(16 * 3, 0.0f);
        const int used = (degree + 1) * (degree + 1) * 3;
        std::copy_n(coeffs.begin(), used, truncated.begin());
        const std::array<double, 3> a = eval_sh(degree, coeffs.data(), dir);
        const std::array<double, 3> b = eval_sh(3, truncated.data(), dir);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-15) << "degree " << degree;
    }
    // Degree 0 is the DC term alone, independent of direction.
    const std::array<double, 3> dc = eval_sh(0, coeffs.data(), {1.0, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(dc[1], kShC0 * static_cast<double>(coeffs[1]));
}

}  // namespace
}  // namespace vksplat::reference
