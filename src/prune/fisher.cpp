// PUP 3D-GS's Fisher information per Gaussian (see fisher.hpp): per pixel the derivative of each
// colour channel with respect to the opacity and 2D footprint of each splat it blends, chained
// through the analytic Jacobian of the splat's projection.
#include "vksplat/prune/fisher.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <glm/gtc/quaternion.hpp>

#include "vksplat/constants.hpp"
#include "vksplat/reference/rasterizer.hpp"
#include "vksplat/reference/sh.hpp"
#include "prune/parallel_for.hpp"

namespace vksplat::prune {
namespace {

using namespace vksplat::constants;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Row6 = Eigen::Matrix<double, 1, 6>;

// How a splat's projection moves with its 6 parameters (mean x, y, z, log-scale 0, 1, 2) in one view.
struct SplatJacobian {
    Eigen::Matrix<double, 5, 6> footprint;  // rows: 2D mean x, y and conic x, y, z (as ProjectedGaussian)
    Eigen::Matrix<double, 3, 6> color;      // rows: r, g, b (only the mean moves them, by the view direction)
};

// The conic's (x, y, z) = (Q00, Q01, Q11) change for a change (da, db, dc) of the 2D covariance
// [[a, b], [b, c]]: dQ = -Q dC Q.
Eigen::Vector3d conic_change(const Eigen::Matrix2d& q, double da, double db, double dc) {
    Eigen::Matrix2d d;
    d << da, db, db, dc;
    const Eigen::Matrix2d dq = -q * d * q;
    return {dq(0, 0), dq(0, 1), dq(1, 1)};
}

// The derivatives of reference::project's mean, conic and colour for a visible Gaussian: the
// perspective mean, the EWA covariance J W Sigma W^T J^T + low-pass with J taken at the clamped view
// position (reference covariance_2d), its inverse, and SH at the view direction clamped at 0.
SplatJacobian splat_jacobian(const GaussianCloud& cloud, size_t index, const Camera& camera, int sh_degree,
                             const reference::ProjectedGaussian& splat) {
    const glm::dvec3 world(cloud.positions[index * 3], cloud.positions[index * 3 + 1], cloud.positions[index * 3 + 2]);
    const glm::dvec3 view = camera.to_camera(world);
    const double x = view.x, y = view.y, z = view.z, fx = camera.fx, fy = camera.fy;
    const double limit_x_pos = (camera.width - camera.cx) / fx + (kJacobianClamp - 1.0) * camera.tan_half_fov_x();
    const double limit_x_neg = camera.cx / fx + (kJacobianClamp - 1.0) * camera.tan_half_fov_x();
    const double limit_y_pos = (camera.height - camera.cy) / fy + (kJacobianClamp - 1.0) * camera.tan_half_fov_y();
    const double limit_y_neg = camera.cy / fy + (kJacobianClamp - 1.0) * camera.tan_half_fov_y();
    const double ux = std::clamp(x / z, -limit_x_neg, limit_x_pos), uy = std::clamp(y / z, -limit_y_neg, limit_y_pos);
    const bool clamped_x = ux != x / z, clamped_y = uy != y / z;
    const double tx = ux * z, ty = uy * z, z2 = z * z, z3 = z2 * z;

    // Rows of J and their derivatives along view x, y, z. A clamped tx is u z: it no longer
    // follows x, and -fx tx / z^2 = -fx u / z falls off as 1/z instead of 1/z^2.
    const glm::dvec3 j0(fx / z, 0.0, -fx * tx / z2), j1(0.0, fy / z, -fy * ty / z2);
    const std::array<glm::dvec3, 3> dj0 = {glm::dvec3(0.0, 0.0, clamped_x ? 0.0 : -fx / z2), glm::dvec3(0.0),
                                           glm::dvec3(-fx / z2, 0.0, (clamped_x ? 1.0 : 2.0) * fx * tx / z3)};
    const std::array<glm::dvec3, 3> dj1 = {glm::dvec3(0.0), glm::dvec3(0.0, 0.0, clamped_y ? 0.0 : -fy / z2),
                                           glm::dvec3(0.0, -fy / z2, (clamped_y ? 1.0 : 2.0) * fy * ty / z3)};
    const glm::dmat3 w_transposed = glm::transpose(camera.rotation);
    const glm::dvec3 t0 = w_transposed * j0, t1 = w_transposed * j1;

    const float* q = &cloud.rotations[index * 4];
    const glm::dmat3 rotation = glm::mat3_cast(glm::normalize(glm::dquat(q[0], q[1], q[2], q[3])));
    std::array<double, 3> variance{};
    glm::dmat3 sigma(0.0);
    for (int k = 0; k < 3; ++k) {
        variance[k] = std::exp(2.0 * double(cloud.log_scales[index * 3 + k]));
        sigma += variance[k] * glm::outerProduct(rotation[k], rotation[k]);
    }
    const double a = glm::dot(t0, sigma * t0) + kLowPassFilter, b = glm::dot(t0, sigma * t1),
                 c = glm::dot(t1, sigma * t1) + kLowPassFilter;
    Eigen::Matrix2d conic;
    conic << c, -b, -b, a;
    conic /= a * c - b * b;

    SplatJacobian jac;
    jac.footprint.setZero();
    jac.color.setZero();
    // Along view x, y, z first, then to world: d view / d world = W, so grad_world = W^T grad_view.
    Eigen::Matrix<double, 5, 3> along_view;
    along_view.row(0) << fx / z, 0.0, -fx * x / z2;
    along_view.row(1) << 0.0, fy / z, -fy * y / z2;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 dt0 = w_transposed * dj0[k], dt1 = w_transposed * dj1[k];
        along_view.block<3, 1>(2, k) = conic_change(conic, 2.0 * glm::dot(dt0, sigma * t0),
                                                    glm::dot(dt0, sigma * t1) + glm::dot(t0, sigma * dt1),
                                                    2.0 * glm::dot(dt1, sigma * t1));
    }
    Eigen::Matrix3d w;  // W[r][c] = camera.rotation[c][r] (glm is column-major)
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) w(r, col) = camera.rotation[col][r];
    jac.footprint.leftCols<3>() = along_view * w;
    // Sigma = sum_k e^(2 s_k) r_k r_k^T, so d Sigma / d s_k = 2 e^(2 s_k) r_k r_k^T.
    for (int k = 0; k < 3; ++k) {
        const double p0 = glm::dot(t0, rotation[k]), p1 = glm::dot(t1, rotation[k]), e = 2.0 * variance[k];
        jac.footprint.block<3, 1>(2, 3 + k) = conic_change(conic, e * p0 * p0, e * p0 * p1, e * p1 * p1);
    }

    // Colour = max(SH(normalize(world - centre)) + 0.5, 0): central differences in double of the
    // reference's own SH (a cubic, so the error is h^2 times its third derivative: ~1e-12 here).
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    const float* sh = &cloud.sh[index * stride];
    const int degree = std::clamp(sh_degree, 0, cloud.sh_degree);
    if (degree > 0) {
        const glm::dvec3 centre = camera.centre();
        const double h = 1e-6 * glm::length(world - centre);
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 step(0.0);
            step[k] = h;
            const auto plus = reference::eval_sh(degree, sh, glm::normalize(world + step - centre));
            const auto minus = reference::eval_sh(degree, sh, glm::normalize(world - step - centre));
            for (int ch = 0; ch < 3; ++ch)
                if (splat.color[ch] > 0.0) jac.color(ch, k) = (plus[ch] - minus[ch]) / (2.0 * h);
        }
    }
    return jac;
}

// What one view needs per Gaussian.
struct ViewSplats {
    std::vector<reference::ProjectedGaussian> projected;
    std::vector<SplatJacobian> jacobian;  // filled for the visible ones
    // Below this power its alpha is surely under 1/255: most of a tile's splats miss most of its
    // pixels, and the test spares them the exp (a margin of 1e-9 leaves the exact test to the rest).
    std::vector<double> min_power;
};

// The visible splats overlapping each tile, in index order.
std::vector<std::vector<uint32_t>> tile_members(const std::vector<reference::ProjectedGaussian>& splats, int tiles_x,
                                                int tiles_y) {
    std::vector<std::vector<uint32_t>> lists(size_t(tiles_x) * size_t(tiles_y));
    for (uint32_t i = 0; i < splats.size(); ++i) {
        const auto& s = splats[i];
        if (!s.visible) continue;
        for (int ty = s.rect_min.y; ty < s.rect_max.y; ++ty)
            for (int tx = s.rect_min.x; tx < s.rect_max.x; ++tx) lists[size_t(ty) * tiles_x + tx].push_back(i);
    }
    return lists;
}

// A tile's members in the reference's blend order: by depth as a float, ties by index.
void sort_for_blending(std::vector<uint32_t>& list, const std::vector<reference::ProjectedGaussian>& splats) {
    std::stable_sort(list.begin(), list.end(),
                     [&](uint32_t l, uint32_t r) { return float(splats[l].depth) < float(splats[r].depth); });
}

// One splat blended into a pixel.
struct Blended {
    uint32_t splat;
    double alpha, transmittance;  // its alpha, and T in front of it
    bool alpha_clamped;           // opacity * G reached kMaxAlpha: alpha no longer follows the footprint
};

// Adds one pixel's sum over channels of g g^T to each splat it blends. With C the final colour
// (background included) and S_i the colour blended up to and including splat i,
//   dC/d alpha_i = c_i T_i - (C - S_i) / (1 - alpha_i)
// (all that is behind i, background included, is scaled by 1 - alpha_i), and alpha_i =
// opacity * exp(power) moves with the 2D mean and conic as alpha_i * d power.
void add_pixel(const ViewSplats& view, const std::vector<uint32_t>& list, glm::dvec2 pixel, const RenderSettings& settings,
               std::vector<Blended>& blended, std::vector<FisherMatrix>& sums) {
    blended.clear();
    double transmittance = 1.0;
    Eigen::Vector3d color = Eigen::Vector3d::Zero();
    for (uint32_t i : list) {  // reference blend_pixel's walk
        const auto& s = view.projected[i];
        const glm::dvec2 d = s.mean - pixel;
        const double power = -0.5 * (s.conic.x * d.x * d.x + s.conic.z * d.y * d.y) - s.conic.y * d.x * d.y;
        if (power > 0.0 || power < view.min_power[i]) continue;
        const double raw = s.opacity * std::exp(power);
        const double alpha = std::min(double(kMaxAlpha), raw);
        if (alpha < kMinAlpha) continue;
        const double next = transmittance * (1.0 - alpha);
        if (next < kMinTransmittance) break;
        blended.push_back({i, alpha, transmittance, raw >= double(kMaxAlpha)});
        color += Eigen::Vector3d(s.color[0], s.color[1], s.color[2]) * (alpha * transmittance);
        transmittance = next;
    }
    const Eigen::Vector3d final_color =
        color + transmittance * Eigen::Vector3d(settings.background[0], settings.background[1], settings.background[2]);

    Eigen::Vector3d so_far = Eigen::Vector3d::Zero();
    for (const Blended& b : blended) {
        const auto& s = view.projected[b.splat];
        const SplatJacobian& jac = view.jacobian[b.splat];
        const Eigen::Vector3d c(s.color[0], s.color[1], s.color[2]);
        const double weight = b.alpha * b.transmittance;
        so_far += c * weight;
        const Eigen::Vector3d d_alpha = c * b.transmittance - (final_color - so_far) / (1.0 - b.alpha);
        Row6 footprint = Row6::Zero();  // d alpha / d parameters
        if (!b.alpha_clamped) {
            const glm::dvec2 d = s.mean - pixel;
            Eigen::Matrix<double, 1, 5> d_power;
            d_power << -(s.conic.x * d.x + s.conic.y * d.y), -(s.conic.z * d.y + s.conic.y * d.x), -0.5 * d.x * d.x,
                -d.x * d.y, -0.5 * d.y * d.y;
            footprint = b.alpha * d_power * jac.footprint;
        }
        Eigen::Map<Mat6> sum(sums[b.splat].data());  // symmetric, so row- or column-major alike
        for (int ch = 0; ch < 3; ++ch) {
            const Row6 g = d_alpha[ch] * footprint + weight * jac.color.row(ch);
            sum.noalias() += g.transpose() * g;
        }
    }
}

}  // namespace

FisherInformation::FisherInformation(const GaussianCloud& cloud, const RenderSettings& settings)
    : cloud_(cloud), settings_(settings) {}

void FisherInformation::add_view(const Camera& camera) {
    camera.validate();
    cloud_.check_consistent();
    const int sh_degree = std::min(cloud_.sh_degree, settings_.max_sh_degree);
    const unsigned workers = worker_count();
    const size_t n = cloud_.size();

    ViewSplats view;
    view.projected.resize(n);
    view.jacobian.resize(n);
    view.min_power.resize(n);
    constexpr size_t kBatch = 1024;
    parallel_for((n + kBatch - 1) / kBatch, workers, [&](size_t batch, unsigned) {
        for (size_t i = batch * kBatch; i < std::min(n, (batch + 1) * kBatch); ++i) {
            view.projected[i] = reference::project(cloud_, i, camera, sh_degree);
            const auto& splat = view.projected[i];
            if (!splat.visible) continue;
            view.jacobian[i] = splat_jacobian(cloud_, i, camera, sh_degree, splat);
            view.min_power[i] = std::log(double(kMinAlpha) / splat.opacity) - 1e-9;
        }
    });

    const int tiles_x = (camera.width + int(kTileWidth) - 1) / int(kTileWidth);
    const int tiles_y = (camera.height + int(kTileHeight) - 1) / int(kTileHeight);
    auto lists = tile_members(view.projected, tiles_x, tiles_y);
    // Each worker sums into its own matrices (kept over the views, added up when asked for): no two
    // threads ever write one Gaussian's sums.
    if (partial_.size() < workers) partial_.resize(workers);
    parallel_for(lists.size(), workers, [&](size_t tile, unsigned worker) {
        if (lists[tile].empty()) return;
        if (partial_[worker].empty()) partial_[worker].assign(n, FisherMatrix{});
        sort_for_blending(lists[tile], view.projected);  // here, so that the sorts share the cores too
        std::vector<Blended> blended;
        const int x0 = int(tile % tiles_x) * int(kTileWidth), y0 = int(tile / tiles_x) * int(kTileHeight);
        for (int y = y0; y < std::min(y0 + int(kTileHeight), camera.height); ++y)
            for (int x = x0; x < std::min(x0 + int(kTileWidth), camera.width); ++x)
                add_pixel(view, lists[tile], glm::dvec2(x, y), settings_, blended, partial_[worker]);
    });
}

std::vector<FisherMatrix> FisherInformation::matrices() const {
    std::vector<FisherMatrix> sums(cloud_.size(), FisherMatrix{});
    for (const auto& part : partial_)
        if (!part.empty())
            for (size_t i = 0; i < sums.size(); ++i)
                for (int e = 0; e < 36; ++e) sums[i][e] += part[i][e];
    return sums;
}

std::vector<float> FisherInformation::log_dets() const {
    const std::vector<FisherMatrix> sums = matrices();
    std::vector<float> scores(sums.size());
    for (size_t i = 0; i < sums.size(); ++i) scores[i] = float(fisher_log_det(sums[i]));
    return scores;
}

double fisher_log_det(const FisherMatrix& fisher) {
    const Eigen::Map<const Mat6> matrix(fisher.data());
    const Eigen::SelfAdjointEigenSolver<Mat6> solver(matrix, Eigen::EigenvaluesOnly);
    double log_det = 0.0;
    for (int k = 0; k < 6; ++k) log_det += std::log(std::max(solver.eigenvalues()[k], 0.0) + kFisherEpsilon);
    return log_det;
}

}  // namespace vksplat::prune
