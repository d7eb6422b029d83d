#pragma once
// 3DGS-MCMC's densification as a plan for DensifyPasses (Kheradmand et al. 2024, "3D Gaussian
// Splatting as Markov Chain Monte Carlo"): the host draws which Gaussians are copied and where the
// transparent ones go from the small geometry download, and the gather moves the bulk on the
// device, as the reference's densification does (densify.hpp).
#include <cstdint>

#include "train/densify.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

// A Gaussian of opacity `opacity` shared by `copies` Gaussians in its place (itself included):
// each copy's opacity, and the factor on its scales. Eq. 9 of the paper: the copies composite to
// the original opacity at the centre, 1 - (1 - o')^n = o, and the integral of the composite's
// profile along any axis equals the original's. More than 51 copies count as 51, as the paper's
// table of binomial coefficients stops there.
struct RelocatedCopy {
    double opacity = 0;
    double scale_factor = 1;
};
RelocatedCopy relocated_copy(double opacity, int copies);

struct RelocationPlan {
    DensifyPlan plan;
    RelocationReport report;
};

// The Gaussians untouched keep their order, parameters and moments; the ones drawn (their opacity
// and scales now shared) and the copies follow, with values of their own and moments at zero.
RelocationPlan plan_relocation(const DensifyInputs& inputs, const RelocationRules& rules, uint64_t seed);

}  // namespace vksplat::train
