#pragma once
// The order along a Morton (Z) curve of a cloud's positions, in which the writers of PlayCanvas's
// formats (compressed PLY, SOG) lay their splats out: neighbours in the file are neighbours in
// space, so a chunk's ranges stay small and a texture's neighbouring texels alike.
#include <cstddef>
#include <vector>

#include "vksplat/scene/scene.hpp"

namespace vksplat::io::detail {

// The indices of the cloud's Gaussians in Morton order of their positions over the scene's box,
// at 21 bits an axis; ties keep their order. Positions must be finite.
std::vector<size_t> morton_order(const GaussianCloud& cloud);

}  // namespace vksplat::io::detail
