// Where a sheet's pair of pictures differs most, zoomed: the largest-error window, its enlarged
// crops and its outline on the full pictures.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "vksplat/eval/metrics.hpp"
#include "vksplat/report/comparison_sheet.hpp"

namespace vksplat::report {
namespace {

void check_window(const ErrorWindow& window, int w, int h) {
    if (window.size <= 0 || window.x < 0 || window.y < 0 || window.x + window.size > w || window.y + window.size > h)
        throw std::invalid_argument("error window (" + std::to_string(window.x) + ", " + std::to_string(window.y) +
                                    ") of size " + std::to_string(window.size) + " is not inside the " +
                                    std::to_string(w) + " x " + std::to_string(h) + " image");
}

// Copies `window` of an RGB image (w wide) into rows [top, top + rows) of `panel`, scaled to fill
// them and the panel's width with nearest-neighbour pixels.
void paste_zoomed(const float* image, int w, const ErrorWindow& window, SheetPanel& panel, int top, int rows) {
    for (int y = 0; y < rows; ++y) {
        const int sy = window.y + y * window.size / rows;
        for (int x = 0; x < panel.width; ++x) {
            const int sx = window.x + x * window.size / panel.width;
            const float* src = image + (static_cast<size_t>(sy) * w + sx) * 3;
            std::copy(src, src + 3, panel.rgb.begin() + (static_cast<ptrdiff_t>(top + y) * panel.width + x) * 3);
        }
    }
}

}  // namespace

ErrorWindow largest_error_window(const float* a, const float* b, int w, int h, int size) {
    if (w <= 0 || h <= 0 || size <= 0)
        throw std::invalid_argument("largest_error_window: image " + std::to_string(w) + " x " + std::to_string(h) +
                                    " and window " + std::to_string(size) + " must be positive");
    size = std::min({size, w, h});
    const std::vector<float> err = eval::error_map(a, b, w, h, 3);
    // Summed-area table, one row and column of zeros first.
    const size_t stride = static_cast<size_t>(w) + 1;
    std::vector<double> sums(stride * (static_cast<size_t>(h) + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            sums[(y + 1) * stride + x + 1] = err[static_cast<size_t>(y) * w + x] + sums[y * stride + x + 1] +
                                             sums[(y + 1) * stride + x] - sums[y * stride + x];
    ErrorWindow best{0, 0, size, -1.0};
    for (int y = 0; y + size <= h; ++y)
        for (int x = 0; x + size <= w; ++x) {
            const double sum = sums[(y + size) * stride + x + size] - sums[y * stride + x + size] -
                               sums[(y + size) * stride + x] + sums[y * stride + x];
            if (sum > best.mean_error) best = {x, y, size, sum};
        }
    best.mean_error /= double(size) * size;
    return best;
}

SheetPanel zoomed_window_panel(const float* a, const float* b, int w, int h, const ErrorWindow& window,
                               std::string caption) {
    check_window(window, w, h);
    SheetPanel panel{std::move(caption), std::max(h / 2, 1), h, {}};
    panel.rgb.assign(static_cast<size_t>(panel.width) * h * 3, 1.0f);
    const int top_rows = h / 2;
    paste_zoomed(a, w, window, panel, 0, top_rows);
    paste_zoomed(b, w, window, panel, top_rows, h - top_rows);
    if (top_rows > 0)  // a white line between the two
        std::fill_n(panel.rgb.begin() + static_cast<ptrdiff_t>(top_rows) * panel.width * 3, panel.width * 3, 1.0f);
    return panel;
}

void outline_window(SheetPanel& panel, const ErrorWindow& window, const std::array<float, 3>& colour) {
    check_window(window, panel.width, panel.height);
    const int thickness = std::min(2, window.size);
    for (int y = window.y; y < window.y + window.size; ++y)
        for (int x = window.x; x < window.x + window.size; ++x) {
            const bool edge = x < window.x + thickness || x >= window.x + window.size - thickness ||
                              y < window.y + thickness || y >= window.y + window.size - thickness;
            if (edge) std::copy(colour.begin(), colour.end(), panel.rgb.begin() + (static_cast<ptrdiff_t>(y) * panel.width + x) * 3);
        }
}

}  // namespace vksplat::report
