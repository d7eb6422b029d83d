// The reference's binning and renderCUDA: per-tile lists in depth order, front-to-back blending.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "reference/tile_grid.hpp"
#include "vksplat/constants.hpp"
#include "vksplat/reference/rasterizer.hpp"

namespace vksplat::reference {
namespace {

using namespace vksplat::constants;

// What blending leaves at one pixel.
struct PixelResult {
    glm::dvec3 color{0.0};
    double transmittance = 1.0;
    double depth_sum = 0.0;   // sum of z * alpha * T
    double weight_sum = 0.0;  // sum of alpha * T
    uint32_t contributors = 0;  // splats blended
};

// The indices of the visible splats overlapping each tile, in the order the reference blends them.
std::vector<std::vector<uint32_t>> tile_lists(const std::vector<ProjectedGaussian>& splats, glm::ivec2 grid) {
    std::vector<std::vector<uint32_t>> lists(static_cast<size_t>(grid.x) * grid.y);
    for (uint32_t i = 0; i < splats.size(); ++i) {
        const ProjectedGaussian& s = splats[i];
        if (!s.visible) continue;
        for (int ty = s.rect_min.y; ty < s.rect_max.y; ++ty)
            for (int tx = s.rect_min.x; tx < s.rect_max.x; ++tx) lists[static_cast<size_t>(ty) * grid.x + tx].push_back(i);
    }
    // The reference sorts 64-bit keys (tile << 32 | float32 depth bits) with a stable radix sort over
    // entries emitted in Gaussian order: within a tile, by depth as a float, ties by index.
    for (auto& list : lists)
        std::stable_sort(list.begin(), list.end(), [&splats](uint32_t l, uint32_t r) {
            return static_cast<float>(splats[l].depth) < static_cast<float>(splats[r].depth);
        });
    return lists;
}

// blend_pixel reports each splat that reaches alpha >= 1/255 here (weight 0 for the one that
// stops the pixel), when the caller gathers statistics. The pixel nearest the splat's projected
// centre also sets its centre weight.
void record(GaussianStats* stats, uint32_t i, double weight, glm::dvec2 mean, glm::dvec2 pixel) {
    if (!stats) return;
    if (std::floor(mean.x + 0.5) == pixel.x && std::floor(mean.y + 0.5) == pixel.y)
        stats->centre_weight[i] = static_cast<float>(weight);
    stats->blend_weight[i] += weight;
    stats->max_weight[i] = std::max(stats->max_weight[i], static_cast<float>(weight));
    ++stats->pixels[i];
}

PixelResult blend_pixel(const std::vector<ProjectedGaussian>& splats, const std::vector<uint32_t>& list, glm::dvec2 pixel,
                        GaussianStats* stats) {
    PixelResult result;
    for (uint32_t i : list) {
        const ProjectedGaussian& s = splats[i];
        const glm::dvec2 d = s.mean - pixel;
        const double power = -0.5 * (s.conic.x * d.x * d.x + s.conic.z * d.y * d.y) - s.conic.y * d.x * d.y;
        if (power > 0.0) continue;
        const double alpha = std::min(static_cast<double>(kMaxAlpha), s.opacity * std::exp(power));
        if (alpha < kMinAlpha) continue;
        const double test_t = result.transmittance * (1.0 - alpha);
        // The splat that would push T below the floor is not blended, and nothing after it is.
        if (test_t < kMinTransmittance) {
            record(stats, i, 0.0, s.mean, pixel);
            break;
        }
        const double weight = alpha * result.transmittance;
        record(stats, i, weight, s.mean, pixel);
        result.color += glm::dvec3(s.color[0], s.color[1], s.color[2]) * weight;
        result.depth_sum += s.depth * weight;
        result.weight_sum += weight;
        result.transmittance = test_t;
        ++result.contributors;
    }
    return result;
}

// Every pixel's blend, row-major, and the projected splats (for the statistics).
struct BlendedImage {
    std::vector<ProjectedGaussian> splats;
    std::vector<PixelResult> pixels;
};

BlendedImage blend_image(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings,
                         GaussianStats* stats) {
    camera.validate();
    cloud.check_consistent();
    const int sh_degree = std::min(cloud.sh_degree, settings.max_sh_degree);
    BlendedImage image;
    image.splats.resize(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) image.splats[i] = project(cloud, i, camera, sh_degree);

    const glm::ivec2 grid = tile_grid(camera);
    const std::vector<std::vector<uint32_t>> lists = tile_lists(image.splats, grid);
    if (stats) {
        stats->resize(cloud.size());
        for (size_t i = 0; i < image.splats.size(); ++i) {
            const ProjectedGaussian& s = image.splats[i];
            if (!s.visible) continue;
            stats->visible[i] = 1;
            stats->screen_x[i] = static_cast<float>(s.mean.x);
            stats->screen_y[i] = static_cast<float>(s.mean.y);
            stats->depth[i] = static_cast<float>(s.depth);
            stats->radius[i] = static_cast<float>(s.radius);
        }
    }
    image.pixels.resize(static_cast<size_t>(camera.width) * camera.height);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const size_t tile = static_cast<size_t>(y / static_cast<int>(kTileHeight)) * grid.x +
                                static_cast<size_t>(x / static_cast<int>(kTileWidth));
            image.pixels[static_cast<size_t>(y) * camera.width + x] =
                blend_pixel(image.splats, lists[tile], glm::dvec2(x, y), stats);
        }
    return image;
}

}  // namespace

RenderOutput render(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings) {
    RenderOutput out;
    const BlendedImage image = blend_image(cloud, camera, settings, settings.gather_stats ? &out.stats : nullptr);
    out.width = camera.width;
    out.height = camera.height;
    const size_t pixels = image.pixels.size();
    out.rgb.resize(pixels * 3);
    out.alpha.resize(pixels);
    out.depth.resize(pixels);
    out.contributors.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const PixelResult& p = image.pixels[i];
        for (int c = 0; c < 3; ++c)
            out.rgb[i * 3 + c] = static_cast<float>(p.color[c] + p.transmittance * settings.background[c]);
        out.alpha[i] = static_cast<float>(1.0 - p.transmittance);
        out.depth[i] = p.weight_sum > 0.0 ? static_cast<float>(p.depth_sum / p.weight_sum) : 0.0f;
        out.contributors[i] = p.contributors;
    }
    return out;
}

std::vector<double> render_rgb(const GaussianCloud& cloud, const Camera& camera, const RenderSettings& settings) {
    const BlendedImage image = blend_image(cloud, camera, settings, nullptr);
    std::vector<double> rgb(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb[i * 3 + c] = image.pixels[i].color[c] + image.pixels[i].transmittance * settings.background[c];
    return rgb;
}

}  // namespace vksplat::reference
