// The reference's preprocessCUDA for one Gaussian, in double precision.
#include <algorithm>
#include <cmath>

#include "vksplat/constants.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/reference/sh.hpp"
#include "reference/tile_grid.hpp"

namespace vksplat::reference {
namespace {

using namespace vksplat::constants;

// Sigma = R S^2 R^T with R the rotation of the normalised quaternion (w, x, y, z) (computeCov3D).
glm::dmat3 covariance_3d(const float* log_scale, const float* quaternion) {
    glm::dvec4 q(quaternion[0], quaternion[1], quaternion[2], quaternion[3]);
    q /= glm::length(q);
    const double r = q[0], x = q[1], y = q[2], z = q[3];
    // glm takes columns; these are the rows of R, hence the transpose.
    const glm::dmat3 rotation = glm::transpose(glm::dmat3(
        glm::dvec3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - r * z), 2.0 * (x * z + r * y)),
        glm::dvec3(2.0 * (x * y + r * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - r * x)),
        glm::dvec3(2.0 * (x * z - r * y), 2.0 * (y * z + r * x), 1.0 - 2.0 * (x * x + y * y))));
    glm::dmat3 variances(0.0);
    for (int k = 0; k < 3; ++k) variances[k][k] = std::exp(2.0 * static_cast<double>(log_scale[k]));
    return rotation * variances * glm::transpose(rotation);
}

// computeCov2D: J W Sigma W^T J^T + low-pass filter, returned as (a, b, c) of [[a, b], [b, c]].
glm::dvec3 covariance_2d(const glm::dmat3& sigma, const glm::dvec3& view, const Camera& camera) {
    // The Jacobian is taken at the view position clamped to a little beyond the image
    // (kJacobianClamp times the half field of view), so splats far off screen stay bounded.
    // The margin is measured from each image edge so an off-centre principal point keeps it.
    const double margin_x = (kJacobianClamp - 1.0) * camera.tan_half_fov_x();
    const double margin_y = (kJacobianClamp - 1.0) * camera.tan_half_fov_y();
    const double limit_x_pos = (camera.width - camera.cx) / camera.fx + margin_x;
    const double limit_x_neg = camera.cx / camera.fx + margin_x;
    const double limit_y_pos = (camera.height - camera.cy) / camera.fy + margin_y;
    const double limit_y_neg = camera.cy / camera.fy + margin_y;
    const double z = view.z;
    const double tx = std::clamp(view.x / z, -limit_x_neg, limit_x_pos) * z;
    const double ty = std::clamp(view.y / z, -limit_y_neg, limit_y_pos) * z;

    // Rows of J W: row r of J times the world-to-camera rotation, i.e. W^T j_r.
    const glm::dmat3 w_transposed = glm::transpose(camera.rotation);
    const glm::dvec3 t0 = w_transposed * glm::dvec3(camera.fx / z, 0.0, -camera.fx * tx / (z * z));
    const glm::dvec3 t1 = w_transposed * glm::dvec3(0.0, camera.fy / z, -camera.fy * ty / (z * z));
    return {glm::dot(t0, sigma * t0) + kLowPassFilter, glm::dot(t0, sigma * t1),
            glm::dot(t1, sigma * t1) + kLowPassFilter};
}

double sigmoid(double logit) { return 1.0 / (1.0 + std::exp(-logit)); }

}  // namespace

ProjectedGaussian project(const GaussianCloud& cloud, size_t index, const Camera& camera, int sh_degree) {
    ProjectedGaussian out;
    const glm::dvec3 world(cloud.positions[index * 3], cloud.positions[index * 3 + 1], cloud.positions[index * 3 + 2]);
    const glm::dvec3 view = camera.to_camera(world);
    out.depth = view.z;
    if (view.z <= kNearPlane) return out;

    out.cov2d = covariance_2d(covariance_3d(&cloud.log_scales[index * 3], &cloud.rotations[index * 4]), view, camera);
    const double a = out.cov2d.x, b = out.cov2d.y, c = out.cov2d.z;
    const double det = a * c - b * b;
    if (det == 0.0) return out;
    out.conic = glm::dvec3(c, -b, a) / det;
    const double mid = 0.5 * (a + c);
    const double spread = std::sqrt(std::max(static_cast<double>(kEigenvalueFloor), mid * mid - det));
    out.radius = static_cast<int>(std::ceil(kRadiusSigmas * std::sqrt(std::max(mid + spread, mid - spread))));

    // ndc2Pix: pixel centres sit at integer coordinates, hence the half-pixel shift.
    out.mean = glm::dvec2(camera.fx * view.x / view.z + camera.cx - 0.5, camera.fy * view.y / view.z + camera.cy - 0.5);
    const TileRect rect = tile_rect(out.mean, out.radius, tile_grid(camera));
    out.rect_min = rect.min;
    out.rect_max = rect.max;
    if (rect.empty()) return out;

    out.opacity = sigmoid(cloud.opacity_logits[index]);
    const int degree = std::clamp(sh_degree, 0, cloud.sh_degree);
    const size_t sh_stride = static_cast<size_t>(cloud.sh_coefficients()) * 3;
    const std::array<double, 3> sh = eval_sh(degree, &cloud.sh[index * sh_stride], glm::normalize(world - camera.centre()));
    for (int k = 0; k < 3; ++k) out.color[k] = std::max(sh[k] + kColorOffset, 0.0);
    out.visible = true;
    return out;
}

}  // namespace vksplat::reference
