#pragma once
// Per-Gaussian SH degree: each Gaussian keeps only the SH bands its colour needs. A Gaussian's
// lower degree is stored as zeros in the cloud's one layout (bands above it zeroed), so renderers
// and writers need no change; entropy-coded formats (SPZ) store the zeros in few bytes, the others
// only gain when every Gaussian drops a band (the cloud's degree then falls; see with_sh_degrees).
//
// What dropping a Gaussian's bands above degree d costs is estimated as its view weight (its blend
// weight, sum of alpha * T over the pixels of the views accumulated; 1 for each when no weights
// are given) times the energy sum c^2 of those bands' coefficients over the three channels: for
// orthonormal real SH the mean over all directions of the squared colour those bands add is that
// energy / 4 pi, so the estimate is proportional to the squared error the drop adds to the views.
#include <cstdint>
#include <span>
#include <vector>

#include "vksplat/scene/scene.hpp"

namespace vksplat::prune {

// Per Gaussian, the highest band with a non-zero coefficient (0 where only the DC term is).
std::vector<uint8_t> sh_degrees_in_use(const GaussianCloud& cloud);

// Per-Gaussian degrees that drop `share` (in [0, 1]) of the cloud's higher bands, N * sh_degree
// bands in all (round(share * N * sh_degree) of them), the cheapest drops first: a band goes only
// with the bands above it, and where drops cost the same the higher band, then the lower index,
// goes first. share 0 keeps every Gaussian at the cloud's degree, 1 puts every one at degree 0.
// `weights` is empty or has one entry per Gaussian. Throws std::invalid_argument for a share
// outside [0, 1] or weights of another size.
std::vector<uint8_t> reduced_sh_degrees(const GaussianCloud& cloud, std::span<const double> weights, double share);

// `cloud` with each Gaussian's bands above degrees[i] zeroed, at the highest degree any Gaussian
// keeps (the cloud's own when it is empty). Throws std::invalid_argument when the sizes differ.
GaussianCloud with_sh_degrees(const GaussianCloud& cloud, std::span<const uint8_t> degrees);

// `cloud` with `share` of its higher bands dropped per Gaussian, the cheapest by `weights` and its
// own coefficients: with_sh_degrees of reduced_sh_degrees (which throws for what it refuses).
GaussianCloud with_sh_share_dropped(const GaussianCloud& cloud, std::span<const double> weights, double share);

}  // namespace vksplat::prune
