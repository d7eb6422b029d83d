#include "eval/image_args.hpp"
#include "vksplat/eval/metrics.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace vksplat::eval {
namespace {

constexpr int kRadius = 5;  // 11 taps: int(3.5 * sigma + 0.5), as skimage/scipy truncate it
constexpr int kWindow = 2 * kRadius + 1;
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;
// Output rows per band. Working in bands keeps every buffer in cache and reuses it, instead of
// first-touching ~50 MB of fresh full-image planes per call (which cost more than the filtering).
constexpr int kBandRows = 32;

// The normalised 1-D Gaussian, with the formula and truncation of scipy.ndimage.gaussian_filter.
cv::Mat gaussian_kernel() {
    cv::Mat k(kWindow, 1, CV_64F);
    double sum = 0.0;
    for (int x = -kRadius; x <= kRadius; ++x) {
        const double w = std::exp(-0.5 / (kSigma * kSigma) * (x * x));
        k.at<double>(x + kRadius) = w;
        sum += w;
    }
    return k / sum;
}

// One channel of one band of the image: its input rows (the output rows plus the window radius
// above and below) and the Gaussian-weighted local moments at its output pixels.
struct Band {
    cv::Mat x, y, sum_sq, cross;      // inputs: x, y, x^2 + y^2, x * y (double, to keep
                                      // E[x^2] - E[x]^2 from cancelling away SSIM's 6th decimal)
    cv::Mat mx, my, m_sum_sq, m_cross;  // their local means at the output pixels
};

// Gaussian-weighted local means of `plane` over `inner`. Filtering an interior view without
// BORDER_ISOLATED makes OpenCV read the real neighbours from the parent: no border rule is ever
// applied, which is what the 'valid' convolution means.
void local_mean(const cv::Mat& plane, const cv::Rect& inner, const cv::Mat& kernel, cv::Mat& out) {
    cv::sepFilter2D(plane(inner), out, CV_64F, kernel, kernel, cv::Point(-1, -1), 0.0,
                    cv::BORDER_REFLECT);
}

// Sum of the SSIM map of channel `ch` over `rows` output rows starting at output row `first`
// (output row r is image row r + kRadius), over the pixels whose `mask` byte is set (all when null).
double band_ssim_sum(const float* a, const float* b, const uint8_t* mask, int width, int channels, int ch,
                     int first, int rows, const cv::Mat& kernel, Band& band) {
    const int in_rows = rows + 2 * kRadius;
    for (cv::Mat* plane : {&band.x, &band.y, &band.sum_sq, &band.cross})
        plane->create(in_rows, width, CV_64F);
    for (int r = 0; r < in_rows; ++r) {
        double* xr = band.x.ptr<double>(r);
        double* yr = band.y.ptr<double>(r);
        // E[x^2] + E[y^2] is filtered as one plane: the filter is linear and SSIM only needs the sum.
        double* sum_sq = band.sum_sq.ptr<double>(r);
        double* cross = band.cross.ptr<double>(r);
        const size_t row = static_cast<size_t>(first + r) * width;
        for (int c = 0; c < width; ++c) {
            const size_t i = (row + c) * channels + ch;
            const double x = detail::clamp01(a[i]), y = detail::clamp01(b[i]);
            xr[c] = x;
            yr[c] = y;
            sum_sq[c] = x * x + y * y;
            cross[c] = x * y;
        }
    }

    const cv::Rect inner(kRadius, kRadius, width - 2 * kRadius, rows);
    local_mean(band.x, inner, kernel, band.mx);
    local_mean(band.y, inner, kernel, band.my);
    local_mean(band.sum_sq, inner, kernel, band.m_sum_sq);
    local_mean(band.cross, inner, kernel, band.m_cross);

    double sum = 0.0;
    for (int r = 0; r < rows; ++r) {
        const double* ux = band.mx.ptr<double>(r);
        const double* uy = band.my.ptr<double>(r);
        const double* uxx_yy = band.m_sum_sq.ptr<double>(r);
        const double* uxy = band.m_cross.ptr<double>(r);
        const uint8_t* mask_row = mask ? mask + static_cast<size_t>(first + r + kRadius) * width + kRadius : nullptr;
        for (int c = 0; c < inner.width; ++c) {
            if (mask_row && !mask_row[c]) continue;
            const double means_sq = ux[c] * ux[c] + uy[c] * uy[c];
            const double covariance = uxy[c] - ux[c] * uy[c];
            const double variances = uxx_yy[c] - means_sq;  // sigma_x^2 + sigma_y^2
            sum += ((2.0 * ux[c] * uy[c] + kC1) * (2.0 * covariance + kC2)) /
                   ((means_sq + kC1) * (variances + kC2));
        }
    }
    return sum;
}

// Mean of the SSIM map over the valid region's pixels in `mask` (all when null); NaN when none.
double mean_ssim(const char* metric, const float* a, const float* b, const uint8_t* mask, int width, int height,
                 int channels) {
    detail::check_image_pair(metric, a, b, width, height, channels);
    if (width < kWindow || height < kWindow)
        throw std::invalid_argument(std::string(metric) + ": image " + std::to_string(width) + " x " +
                                    std::to_string(height) + " is smaller than the " +
                                    std::to_string(kWindow) + " x " + std::to_string(kWindow) +
                                    " window");

    const cv::Mat kernel = gaussian_kernel();
    const int out_width = width - 2 * kRadius;
    const int out_height = height - 2 * kRadius;
    double counted = static_cast<double>(out_width) * out_height;
    if (mask) {
        counted = 0;
        for (int y = kRadius; y < height - kRadius; ++y)
            for (int x = kRadius; x < width - kRadius; ++x) counted += mask[static_cast<size_t>(y) * width + x] != 0;
        if (counted == 0) return NAN;
    }
    const int bands = (out_height + kBandRows - 1) / kBandRows;
    // One task per (channel, band), run on OpenCV's thread pool. Each task writes its own slot and
    // the slots are summed in order afterwards, so the result does not depend on the thread count.
    std::vector<double> sums(static_cast<size_t>(channels) * bands);
    cv::parallel_for_(cv::Range(0, static_cast<int>(sums.size())), [&](const cv::Range& tasks) {
        Band band;
        for (int t = tasks.start; t < tasks.end; ++t) {
            const int first = (t % bands) * kBandRows;
            const int rows = std::min(kBandRows, out_height - first);
            sums[t] = band_ssim_sum(a, b, mask, width, channels, t / bands, first, rows, kernel, band);
        }
    });
    double total = 0.0;
    for (int ch = 0; ch < channels; ++ch) {
        double channel_sum = 0.0;
        for (int i = 0; i < bands; ++i) channel_sum += sums[static_cast<size_t>(ch) * bands + i];
        total += channel_sum / counted;
    }
    return total / channels;
}

}  // namespace

double ssim(const float* a, const float* b, int width, int height, int channels) {
    return mean_ssim("ssim", a, b, nullptr, width, height, channels);
}

double masked_ssim(const float* a, const float* b, const uint8_t* mask, int width, int height, int channels) {
    if (!mask) throw std::invalid_argument("masked_ssim: null mask");
    return mean_ssim("masked_ssim", a, b, mask, width, height, channels);
}

}  // namespace vksplat::eval
