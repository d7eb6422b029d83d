// RenderSettings::validate(): the settings a frame is drawn with, checked where every frame's
// parameters are made (frame_layout.cpp).
#include <cmath>
#include <cstdio>

#include "vksplat/error.hpp"
#include "vksplat/render_types.hpp"

namespace vksplat {

void RenderSettings::validate() const {
    for (const float channel : background) {
        if (std::isfinite(channel) && channel >= 0.0f && channel <= 1.0f) continue;
        char shown[96];
        std::snprintf(shown, sizeof(shown), "background (%g, %g, %g)", double(background[0]), double(background[1]),
                      double(background[2]));
        throw InputError(shown, "each channel must be a finite number in [0, 1]");
    }
}

}  // namespace vksplat
