#pragma once
// Settings and outputs shared by the GPU renderer and the reference rasterizer.
#include <array>
#include <cstdint>
#include <vector>

namespace vksplat {

struct RenderSettings {
    std::array<float, 3> background{0.f, 0.f, 0.f};
    int max_sh_degree = 3;   // SH bands above this are ignored (capped by the scene's degree)
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
    // The reference's n_contrib: how many depth-ordered splats of the pixel's tile were walked up
    // to and including the last one that contributed.
    std::vector<uint32_t> contributors;
};

}  // namespace vksplat
