// Camera::validate(): rejects cameras that would make the renderer divide by zero or produce a
// sheared, mirrored or NaN image, with a message a user can trace back to the camera file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "vksplat/camera/camera.hpp"
#include "vksplat/error.hpp"

namespace vksplat {
namespace {

// Camera files store rotations in float or with a handful of digits; anything closer to
// orthonormal than this is a rotation up to rounding.
constexpr double kOrthonormalTolerance = 1e-4;

// Focal lengths, in multiples of the image's size in pixels (fx of the width, fy of the height),
// that still make a picture. Real cameras lie far inside: about 0.3 (a 120 degree view) to 10 (a
// long telephoto). Below 1e-3 the view is within a quarter degree of 180 degrees, which no pinhole
// camera sees; above 1e7 it is under 1e-7 radians wide, and from 3.4e38 the float32 focal length
// the GPU projects with is infinite, every splat lands nowhere and the picture is blank. So the
// bounds are generous and refuse only values that must be mistakes (a unit slip, an overflow).
constexpr double kMinFocalPerPixel = 1e-3;
constexpr double kMaxFocalPerPixel = 1e7;

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
    const double fx_ratio = fx / width, fy_ratio = fy / height;
    if (fx_ratio < kMinFocalPerPixel || fx_ratio > kMaxFocalPerPixel || fy_ratio < kMinFocalPerPixel ||
        fy_ratio > kMaxFocalPerPixel) {
        char shown[160];
        std::snprintf(shown, sizeof(shown), "focal length (%g, %g) makes no picture of a %dx%d image", fx, fy,
                      width, height);
        return std::string(shown) + ": fx / width and fy / height must lie in [1e-3, 1e7]";
    }
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
