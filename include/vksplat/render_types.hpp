#pragma once
// Settings and outputs shared by the GPU renderer and the reference rasterizer.
#include <array>
#include <cstdint>
#include <vector>

namespace vksplat {

struct RenderSettings {
    std::array<float, 3> background{0.f, 0.f, 0.f};
    int max_sh_degree = 3;   // SH bands above this are ignored (capped by the scene's degree)
    // Also measure, per Gaussian, what it contributed to this view (RenderOutput::stats). Costs
    // atomics in the blend pass, so plain rendering leaves it off and pays nothing for it.
    bool gather_stats = false;

    // Throws InputError naming the background unless each channel is a finite number in [0, 1]:
    // it shows wherever the splats leave light through, so a NaN or out-of-range channel would
    // silently colour (or, once written as a picture, clamp) every such pixel. Every GPU frame,
    // rendered or trained, checks its settings with this.
    void validate() const;
};

// What each Gaussian did in one view, indexed like the cloud given to the renderer (Gaussians
// that sanitising dropped stay zero). Filled only when RenderSettings::gather_stats is set.
struct GaussianStats {
    std::vector<uint8_t> visible;     // survived culling (near plane, empty tile rectangle)
    std::vector<float> screen_x;      // projected centre in pixels (pixel centres at integers)
    std::vector<float> screen_y;
    std::vector<float> depth;         // view-space depth
    std::vector<float> radius;        // projected radius in pixels, ceil(3 sigma); 0 if not visible
    std::vector<double> blend_weight; // sum over pixels of alpha * T it contributed
    std::vector<float> max_weight;    // max over pixels of alpha * T
    // Pixels where its alpha reached 1/255: it contributed there, or it stopped the pixel at the
    // transmittance floor. A Gaussian with 0 here in every view can go without changing any of
    // those views' pixels.
    std::vector<uint32_t> pixels;
    // alpha * T at the pixel nearest its projected centre: 0 where that pixel was already opaque
    // before the splat was reached (occluded there) or the splat was too faint to blend.
    std::vector<float> centre_weight;

    void resize(size_t n) {
        visible.assign(n, 0);
        for (auto* v : {&screen_x, &screen_y, &depth, &radius, &max_weight, &centre_weight}) v->assign(n, 0.0f);
        blend_weight.assign(n, 0.0);
        pixels.assign(n, 0);
    }
    size_t size() const { return visible.size(); }
};

// Per-Gaussian statistics summed over views (Renderer::render_stats_totals), indexed like the cloud
// given to set_scene (0 for a Gaussian sanitising dropped).
struct GaussianTotals {
    std::vector<double> blend_weight;       // sum over views and pixels of alpha * T
    std::vector<float> max_weight;          // max over views and pixels of alpha * T
    std::vector<uint64_t> pixels;           // GaussianStats::pixels summed over views
    // Sum over the views where it survived culling of its radius squared (pixels^2; a radius
    // counts at most 2^24 pixels, far beyond any image, to keep the sum in 64 bits).
    std::vector<uint64_t> radius_squared;
    std::vector<uint32_t> views_visible;    // views in which it survived culling
    size_t views = 0;                       // how many views were summed

    void resize(size_t n) {
        blend_weight.assign(n, 0.0);
        max_weight.assign(n, 0.0f);
        pixels.assign(n, 0);
        radius_squared.assign(n, 0);
        views_visible.assign(n, 0);
    }
    size_t size() const { return blend_weight.size(); }
};

// Images are row-major, top row first. rgb has 3 floats per pixel, unclamped above
// (the reference's forward output; writers clamp to [0, 1]).
struct RenderOutput {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;             // colour + background * T
    std::vector<float> alpha;           // 1 - T (final transmittance)
    // Expected depth of the blended surface: sum(w_i z_i) / sum(w_i) with w_i = alpha_i T_i and
    // z_i the view-space depth; 0 where nothing was blended.
    std::vector<float> depth;
    // How many splats were blended into the pixel. (Not the reference's n_contrib, which counts
    // the splats of the tile's list walked up to the last contributor and so depends on how
    // tightly tiles are culled; this count does not.)
    std::vector<uint32_t> contributors;
    GaussianStats stats;
};

}  // namespace vksplat
