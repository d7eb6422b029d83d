#pragma once
// The reference's screen tiling: 16 x 16 pixel tiles, and getRect's tile rectangle of a splat.
#include <algorithm>

#include <glm/glm.hpp>

#include "vksplat/camera/camera.hpp"
#include "vksplat/constants.hpp"

namespace vksplat::reference {

// Tiles [min.x, max.x) x [min.y, max.y).
struct TileRect {
    glm::ivec2 min{0};
    glm::ivec2 max{0};
    bool empty() const { return max.x <= min.x || max.y <= min.y; }
};

// Tiles across and down; the last column and row may be partly outside the image.
inline glm::ivec2 tile_grid(const Camera& camera) {
    return {(camera.width + static_cast<int>(constants::kTileWidth) - 1) / static_cast<int>(constants::kTileWidth),
            (camera.height + static_cast<int>(constants::kTileHeight) - 1) / static_cast<int>(constants::kTileHeight)};
}

// The reference truncates toward zero ((int) cast) and then clamps to [0, grid]. Clamping the
// value to [-1, grid] first gives the same result and keeps far-off splats from overflowing int.
inline int tile_bound(double tiles, int grid) {
    return std::clamp(static_cast<int>(std::clamp(tiles, -1.0, static_cast<double>(grid))), 0, grid);
}

// getRect: the tiles the square of half-side `radius` around `mean` (pixels) overlaps.
inline TileRect tile_rect(glm::dvec2 mean, int radius, glm::ivec2 grid) {
    const double w = constants::kTileWidth, h = constants::kTileHeight;
    return {{tile_bound((mean.x - radius) / w, grid.x), tile_bound((mean.y - radius) / h, grid.y)},
            {tile_bound((mean.x + radius + w - 1.0) / w, grid.x), tile_bound((mean.y + radius + h - 1.0) / h, grid.y)}};
}

}  // namespace vksplat::reference
