#pragma once
// Gaussians in Morton (Z-curve) order of their positions: neighbours in space become neighbours in
// memory, so the splats a tile blends, and the gradients its backward pass adds, touch fewer cache
// lines (VkSplat re-orders this way every 100 steps). Training re-orders after densification when
// TrainOptions::spatial_order is on.
#include <cstdint>
#include <vector>

namespace vksplat::train {

// The order of `count` points (xyz interleaved) along the Z-curve through their bounding box, 21
// bits per axis; points with a non-finite coordinate go last, in their order.
std::vector<uint32_t> morton_order(const float* positions, uint32_t count);

}  // namespace vksplat::train
