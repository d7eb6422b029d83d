// The reference trainer's loss, l1_loss and ssim of utils/loss_utils.py, in double precision,
// with its gradient by hand.
#include "vksplat/reference/training_loss.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace vksplat::reference {
namespace {

constexpr int kRadius = 5;  // window_size 11
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;

// gaussian() of loss_utils.py: the normalised 1D Gaussian. The 2D window is its outer product.
std::array<double, 2 * kRadius + 1> gaussian_window() {
    std::array<double, 2 * kRadius + 1> g{};
    double sum = 0;
    for (int i = -kRadius; i <= kRadius; ++i) {
        g[i + kRadius] = std::exp(-double(i * i) / (2.0 * kSigma * kSigma));
        sum += g[i + kRadius];
    }
    for (double& w : g) w /= sum;
    return g;
}

double sign(double v) { return v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0; }

}  // namespace

TrainingLoss training_loss(int width, int height, std::span<const double> rendered_rgb,
                           std::span<const float> photo_rgb, std::span<const uint8_t> mask, double ssim_weight) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("training_loss: the image is empty");
    const size_t pixels = size_t(width) * size_t(height);
    if (rendered_rgb.size() != 3 * pixels || photo_rgb.size() != 3 * pixels || (!mask.empty() && mask.size() != pixels))
        throw std::invalid_argument("training_loss: an input's size does not match the image");

    const auto g = gaussian_window();
    const double count = 3.0 * double(pixels);
    const double lambda = ssim_weight;
    const auto inside = [&](int px, int py) { return px >= 0 && py >= 0 && px < width && py < height; };
    const auto at = [&](int px, int py) { return size_t(py) * size_t(width) + size_t(px); };
    const auto weight_of = [&](size_t p) { return mask.empty() || mask[p] != 0 ? 1.0 : 0.0; };

    TrainingLoss out;
    out.gradient.assign(3 * pixels, 0.0);
    // Per pixel of one channel: dL/d(G*x), dL/d(G*x^2), dL/d(G*(xy)) through that pixel's SSIM term.
    std::vector<double> d_mean(pixels), d_square(pixels), d_cross(pixels);
    for (int ch = 0; ch < 3; ++ch) {
        const auto x = [&](size_t p) { return rendered_rgb[3 * p + ch]; };
        const auto y = [&](size_t p) { return double(photo_rgb[3 * p + ch]); };

        for (int py = 0; py < height; ++py) {
            for (int px = 0; px < width; ++px) {
                // The window's moments; pixels outside the image are 0 (padding 5).
                double mu_x = 0, mu_y = 0, e_xx = 0, e_yy = 0, e_xy = 0;
                for (int dy = -kRadius; dy <= kRadius; ++dy) {
                    for (int dx = -kRadius; dx <= kRadius; ++dx) {
                        if (!inside(px + dx, py + dy)) continue;
                        const size_t q = at(px + dx, py + dy);
                        const double w = g[dy + kRadius] * g[dx + kRadius];
                        mu_x += w * x(q);
                        mu_y += w * y(q);
                        e_xx += w * x(q) * x(q);
                        e_yy += w * y(q) * y(q);
                        e_xy += w * x(q) * y(q);
                    }
                }
                const double var_x = e_xx - mu_x * mu_x;
                const double var_y = e_yy - mu_y * mu_y;
                const double cov = e_xy - mu_x * mu_y;
                const double a = 2 * mu_x * mu_y + kC1, b = 2 * cov + kC2;
                const double c = mu_x * mu_x + mu_y * mu_y + kC1, d = var_x + var_y + kC2;
                const double s = a * b / (c * d);

                const size_t p = at(px, py);
                const double m = weight_of(p);
                const double diff = x(p) - y(p);
                out.ssim += m * s;
                out.l1 += m * std::abs(diff);
                out.mse += m * diff * diff;
                out.gradient[3 * p + ch] += (1 - lambda) * m * sign(diff) / count;

                // s = a b / (c d) as a function of mu_x, var_x and cov (quotient rule) ...
                const double ds_dmu_x = 2 * mu_y * b / (c * d) - s * 2 * mu_x / c;
                const double ds_dvar_x = -s / d;
                const double ds_dcov = 2 * a / (c * d);
                // ... and of the filtered planes: var_x = G*x^2 - mu_x^2, cov = G*(xy) - mu_x mu_y, mu_x = G*x.
                const double dl_ds = -lambda * m / count;
                d_mean[p] = dl_ds * (ds_dmu_x - 2 * mu_x * ds_dvar_x - mu_y * ds_dcov);
                d_square[p] = dl_ds * ds_dvar_x;
                d_cross[p] = dl_ds * ds_dcov;
            }
        }

        // x at q enters the planes of every p in its window: G*x with weight G(p - q), G*x^2 with
        // G(p - q) 2 x_q, G*(xy) with G(p - q) y_q.
        for (int qy = 0; qy < height; ++qy) {
            for (int qx = 0; qx < width; ++qx) {
                const size_t q = at(qx, qy);
                double sum = 0;
                for (int dy = -kRadius; dy <= kRadius; ++dy) {
                    for (int dx = -kRadius; dx <= kRadius; ++dx) {
                        if (!inside(qx + dx, qy + dy)) continue;
                        const size_t p = at(qx + dx, qy + dy);
                        const double w = g[dy + kRadius] * g[dx + kRadius];
                        sum += w * (d_mean[p] + 2 * x(q) * d_square[p] + y(q) * d_cross[p]);
                    }
                }
                out.gradient[3 * q + ch] += sum;
            }
        }
    }
    out.l1 /= count;
    out.ssim /= count;
    out.mse /= count;
    out.loss = (1 - lambda) * out.l1 + lambda * (1 - out.ssim);
    return out;
}

}  // namespace vksplat::reference
