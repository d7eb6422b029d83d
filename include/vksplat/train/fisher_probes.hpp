#pragma once
// PUP 3D-GS's Fisher information per Gaussian (prune/fisher.hpp defines it: F = sum over views,
// pixels and colour channels of g g^T, g = d C / d (mean, log-scales)) estimated on the GPU with the
// backward pass: for each probe every pixel channel's upstream gradient is a random sign eps, the
// backward pass returns G = sum eps g, and E[G G^T] = F because the cross terms have mean zero.
// Each probe adds one rank-one term per Gaussian, so `probes_per_view` of them estimate a view's
// share with a relative spread of about sqrt(2 / probes) per view, shrinking with the views that
// see a Gaussian; the footprint on screen has 5 parameters, so fewer than 5 probes a view would
// also leave directions that one view constrains unseen. prune::FisherInformation computes F
// exactly on the CPU (in double, every pixel walked): the oracle these estimates are tested against,
// and too slow for real scenes (the 254 views of the 400k bonsai took over 8 minutes on 16 cores).
//
//   std::vector<prune::FisherMatrix> f = train::estimate_fisher(context, cloud, cameras, settings);
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::train {

struct FisherProbeOptions {
    uint32_t probes_per_view = 8;
    uint32_t seed = 0;  // the signs of every probe follow from it, the view's index and the probe's
};

// Per Gaussian, F summed over `cameras` as a row-major 6x6 over (mean x, y, z, log-scale 0, 1, 2)
// (prune::FisherMatrix's layout), from float sums on the device. `progress(done, total)` after each
// view. Throws std::invalid_argument if the cloud needs sanitising or probes_per_view is 0,
// InputError for an invalid camera.
std::vector<std::array<double, 36>> estimate_fisher(const gpu::Context& context, const GaussianCloud& cloud,
                                                    const std::vector<Camera>& cameras, const RenderSettings& settings,
                                                    const FisherProbeOptions& options = {},
                                                    const std::function<void(size_t, size_t)>& progress = {});

}  // namespace vksplat::train
