#include "display_modes.hpp"

#include <cmath>

namespace vksplat::viewer {

const char* to_string(DisplayMode mode) {
    switch (mode) {
        case DisplayMode::splats: return "splats";
        case DisplayMode::points: return "points";
        case DisplayMode::ellipsoids: return "ellipsoids";
    }
    return "?";
}

DisplayMode next(DisplayMode mode) {
    return mode == DisplayMode::splats ? DisplayMode::points
           : mode == DisplayMode::points ? DisplayMode::ellipsoids
                                         : DisplayMode::splats;
}

GaussianCloud display_cloud(const GaussianCloud& scene, DisplayMode mode, double scale, double point_size) {
    GaussianCloud out = scene;
    const float log_scale = float(std::log(scale)), log_point = float(std::log(point_size));
    const float opaque = float(std::log(0.99 / 0.01));  // the logit of 0.99, the blend's alpha cap
    for (size_t i = 0; i < out.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            float& s = out.log_scales[3 * i + k];
            s = mode == DisplayMode::points ? log_point : s + log_scale;
        }
        if (mode != DisplayMode::splats) out.opacity_logits[i] = opaque;
    }
    return out;
}

}  // namespace vksplat::viewer
