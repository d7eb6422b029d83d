// Camera::validate(): rejects cameras that would make the renderer divide by zero or produce a
// sheared, mirrored or NaN image, with a message a user can trace back to the camera file.
#include <algorithm>
#include <cmath>
#include <string>

#include "vksplat/camera.hpp"
#include "vksplat/error.hpp"

namespace vksplat {
namespace {

// Camera files store rotations in float or with a handful of digits; anything closer to
// orthonormal than this is a rotation up to rounding.
constexpr double kOrthonormalTolerance = 1e-4;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::dmat3& m) { return finite(m[0]) && finite(m[1]) && finite(m[2]); }

// Largest deviation of R^T R from the identity.
double orthonormality_error(const glm::dmat3& r) {
    const glm::dmat3 gram = glm::transpose(r) * r;
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(gram[c][k] - (c == k ? 1.0 : 0.0)));
    return worst;
}

}  // namespace

std::string Camera::problem() const {
    if (width <= 0 || height <= 0)
        return "image size " + std::to_string(width) + "x" + std::to_string(height) + " is not positive";
    if (!std::isfinite(fx) || !std::isfinite(fy) || fx <= 0.0 || fy <= 0.0)
        return "focal length (" + std::to_string(fx) + ", " + std::to_string(fy) + ") must be positive and finite";
    if (!std::isfinite(cx) || !std::isfinite(cy))
        return "principal point (" + std::to_string(cx) + ", " + std::to_string(cy) + ") is not finite";
    if (!finite(translation)) return "translation is not finite";
    if (!finite(rotation)) return "rotation is not finite";
    if (const double error = orthonormality_error(rotation); error > kOrthonormalTolerance)
        return "rotation is not orthonormal (R^T R differs from the identity by " + std::to_string(error) + ")";
    if (glm::determinant(rotation) < 0.0) return "rotation is a reflection (determinant < 0)";
    return {};
}

void Camera::validate() const {
    if (const std::string what = problem(); !what.empty()) throw InputError("camera '" + name + "'", what);
}

}  // namespace vksplat
