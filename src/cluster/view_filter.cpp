// Scores a region map for the view filter (see view_filter.hpp).
#include "vksplat/cluster/view_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <unordered_map>

namespace vksplat::cluster {
namespace {

// Sobel gradient magnitude of the colour picture (the channels' gradients combined, so that parts
// of equal brightness but different hue are still told apart); 0 on the one-pixel border.
std::vector<float> gradient_magnitude(const std::vector<float>& rgb, int w, int h) {
    std::vector<float> out(size_t(w) * h, 0.0f);
    auto g = [&](int x, int y, int c) { return rgb[(size_t(y) * w + x) * 3 + c]; };
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            float squared = 0;
            for (int c = 0; c < 3; ++c) {
                const float gx = g(x + 1, y - 1, c) + 2 * g(x + 1, y, c) + g(x + 1, y + 1, c) - g(x - 1, y - 1, c) -
                                 2 * g(x - 1, y, c) - g(x - 1, y + 1, c);
                const float gy = g(x - 1, y + 1, c) + 2 * g(x, y + 1, c) + g(x + 1, y + 1, c) - g(x - 1, y - 1, c) -
                                 2 * g(x, y - 1, c) - g(x + 1, y - 1, c);
                squared += gx * gx + gy * gy;
            }
            out[size_t(y) * w + x] = std::sqrt(squared);
        }
    return out;
}

std::string format(const char* pattern, double a, double b) {
    char text[160];
    std::snprintf(text, sizeof(text), pattern, a, b);
    return text;
}

}  // namespace

ViewQuality assess_view(const RegionMap& map, const std::vector<float>& rgb, const ViewFilterParams& params) {
    const int w = map.width, h = map.height;
    const size_t pixels = size_t(w) * size_t(h);
    if (map.labels.size() != pixels || rgb.size() != pixels * 3)
        throw std::invalid_argument("assess_view: region map and render sizes disagree");
    ViewQuality q;
    std::unordered_map<int32_t, size_t> area;
    size_t labelled = 0;
    for (int32_t id : map.labels)
        if (id >= 0) {
            ++area[id];
            ++labelled;
        }
    q.regions = area.size();
    q.labelled_fraction = pixels ? double(labelled) / double(pixels) : 0.0;
    size_t largest = 0;
    for (const auto& [id, count] : area) largest = std::max(largest, count);
    q.largest_fraction = labelled ? double(largest) / double(labelled) : 0.0;

    // Borders between two regions, against the mean over the labelled pixels off the subject's
    // outline: the outline lies on an edge of the render whatever the regions are, so counting it
    // on either side would flatter or blur the comparison.
    const std::vector<float> gradient = gradient_magnitude(rgb, w, h);
    const auto labelled_at = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && map.at(x, y) >= 0; };
    double border_sum = 0, inside_sum = 0;
    size_t inside = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int32_t id = map.at(x, y);
            if (id < 0) continue;
            if (!labelled_at(x - 1, y) || !labelled_at(x + 1, y) || !labelled_at(x, y - 1) || !labelled_at(x, y + 1))
                continue;  // on the outline
            const float g = gradient[size_t(y) * w + x];
            inside_sum += g;
            ++inside;
            if (map.at(x + 1, y) != id || map.at(x, y + 1) != id) {
                border_sum += g;
                ++q.border_pixels;
            }
        }
    if (q.border_pixels > 0 && inside_sum > 0)
        q.edge_alignment = (border_sum / double(q.border_pixels)) / (inside_sum / double(inside));

    if (q.labelled_fraction < params.min_labelled_fraction)
        q.reason = format("no subject: %.1f%% of the pixels carry a region (minimum %.1f%%)",
                          100 * q.labelled_fraction, 100 * params.min_labelled_fraction);
    else if (q.largest_fraction > params.max_largest_fraction)
        q.reason = format("one region covers %.1f%% of the labelled pixels (maximum %.1f%%)",
                          100 * q.largest_fraction, 100 * params.max_largest_fraction);
    else if (q.regions > params.max_regions)
        q.reason = format("%.0f regions (maximum %.0f): noise rather than parts", double(q.regions),
                          double(params.max_regions));
    else if (q.border_pixels > 0 && q.edge_alignment < params.min_edge_alignment)
        q.reason = format("region borders ignore the picture's edges (alignment %.2f, minimum %.2f)",
                          q.edge_alignment, params.min_edge_alignment);
    q.keep = q.reason.empty();
    return q;
}

}  // namespace vksplat::cluster
