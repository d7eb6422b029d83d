#pragma once
// The Gaussians training starts from, as the reference trainer makes them (create_from_pcd): one per
// point, its colour as the SH DC term (higher bands 0), isotropic scale the root of the mean squared
// distance to its 3 nearest points, identity rotation, opacity 0.1.
#include <array>
#include <cstdint>

#include "vksplat/io/sfm_points.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::train {

// Throws InputError for no points, or for a point with a non-finite coordinate: in the neighbour
// search it would throw off the scales of the others (io::read_sfm_points drops such points).
GaussianCloud initial_cloud(const io::SfmPoints& points, int sh_degree);

// `count` points uniform in the box [low, high]^3 with near-grey random colours: what the reference
// starts NeRF-synthetic scenes from (100,000 points in [-1.3, 1.3]^3).
io::SfmPoints random_points(size_t count, float low, float high, uint64_t seed);

}  // namespace vksplat::train
