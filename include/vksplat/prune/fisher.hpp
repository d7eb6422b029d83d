#pragma once
// PUP 3D-GS's sensitivity score (Hanson, Tu et al., "PUP 3D-GS: Principled Uncertainty Pruning for
// 3D Gaussian Splatting", arXiv 2406.10219; github.com/j-alex-hanson/gaussian-splatting-pup,
// fisher_pool_xyz_scaling.py and prune_finetune.py): per Gaussian the Fisher information
//   F = sum over views, pixels p and colour channels c of  g g^T,   g = d C_c(p) / d (mean, log-scale)
// a 6x6 matrix over the Gaussian's world mean (x, y, z) and its log-scales (the stored `_scaling` of
// the INRIA trainer, which their autograd differentiates), every channel of every pixel at full
// resolution (their --pool-resolution 1), and the score log det F. We add kFisherEpsilon to every
// eigenvalue (their code takes the log of the singular values as they are): a Gaussian no pixel
// sees then scores 6 log(epsilon), below every Gaussian some pixel sees, instead of -infinity.
//
// Computed on the CPU in double precision from the reference rasterizer's projection
// (reference::project) and its blending rules: analytic derivatives of the picture it renders (the
// SH colour's along the view direction by central differences in double, to about 1e-12), which is
// the GPU renderer's to float rounding. On the CPU because the per-pixel walk needs the renderer's
// tile lists, which the prune module does not reach into. Cost: a walk of every pixel's tile list
// per view and the Jacobian of each visible Gaussian's projection, spread over the host's cores,
// with a 6x6 sum per Gaussian per core. The sums depend on the number of cores by rounding only.
//
//   prune::FisherInformation fisher(cloud, settings);
//   for (size_t v : views) fisher.add_view(cameras[v]);
//   std::vector<float> scores = fisher.log_dets();
#include <array>
#include <cstddef>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::prune {

// Added to each eigenvalue of F before the log, in colour^2 per (world unit or log-scale unit)^2:
// small against what a Gaussian that covers pixels shows along its mean, but a direction the
// views hardly constrain can fall near it, and then it bounds that direction's share of the score.
// One view alone leaves a direction with none at all but for the colour's view dependence (the
// footprint on screen has 5 parameters, the Gaussian 6): on 4 views of snowmiku, 17,061 of the
// 46,543 Gaussians some pixel sees have a zero eigenvalue, which counts as log(1e-12) = -27.6 in
// their score.
inline constexpr double kFisherEpsilon = 1e-12;

// Row-major 6x6 over (mean x, y, z, log-scale 0, 1, 2).
using FisherMatrix = std::array<double, 36>;

class FisherInformation {
public:
    // `settings` gives the background and SH degree, as for a render. Keeps a reference to `cloud`,
    // which must outlive this and be sanitised (finite values, normalisable rotations).
    FisherInformation(const GaussianCloud& cloud, const RenderSettings& settings);

    // Adds every pixel of one view. Throws if the camera fails Camera::validate().
    void add_view(const Camera& camera);

    // Per Gaussian, F summed over the views added.
    std::vector<FisherMatrix> matrices() const;
    // Per Gaussian, log det(F + kFisherEpsilon I).
    std::vector<float> log_dets() const;

private:
    const GaussianCloud& cloud_;
    RenderSettings settings_;
    // Per worker thread, its share of each Gaussian's sum (empty for a worker that had no tile).
    std::vector<std::vector<FisherMatrix>> partial_;
};

// log det(F + kFisherEpsilon I) from F's eigenvalues (negative rounding noise counts as 0).
double fisher_log_det(const FisherMatrix& fisher);

}  // namespace vksplat::prune
