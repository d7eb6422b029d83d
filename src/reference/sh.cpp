// computeColorFromSH of the reference rasterizer, term for term, in double precision.
#include "vksplat/reference/sh.hpp"

namespace vksplat::reference {

std::array<double, 3> eval_sh(int degree, const float* coeffs, glm::dvec3 dir) {
    const auto sh = [coeffs](int k) {
        return glm::dvec3(coeffs[3 * k], coeffs[3 * k + 1], coeffs[3 * k + 2]);
    };
    glm::dvec3 result = kShC0 * sh(0);
    if (degree > 0) {
        const double x = dir.x, y = dir.y, z = dir.z;
        result = result - kShC1 * y * sh(1) + kShC1 * z * sh(2) - kShC1 * x * sh(3);
        if (degree > 1) {
            const double xx = x * x, yy = y * y, zz = z * z;
            const double xy = x * y, yz = y * z, xz = x * z;
            result = result + kShC2[0] * xy * sh(4) + kShC2[1] * yz * sh(5) +
                     kShC2[2] * (2.0 * zz - xx - yy) * sh(6) + kShC2[3] * xz * sh(7) +
                     kShC2[4] * (xx - yy) * sh(8);
            if (degree > 2) {
                result = result + kShC3[0] * y * (3.0 * xx - yy) * sh(9) + kShC3[1] * xy * z * sh(10) +
                         kShC3[2] * y * (4.0 * zz - xx - yy) * sh(11) +
                         kShC3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * sh(12) +
                         kShC3[4] * x * (4.0 * zz - xx - yy) * sh(13) + kShC3[5] * z * (xx - yy) * sh(14) +
                         kShC3[6] * x * (xx - 3.0 * yy) * sh(15);
            }
        }
    }
    return {result.x, result.y, result.z};
}

}  // namespace vksplat::reference
