#pragma once
// Training to a Gaussian budget the way 3DGS-MCMC does (Kheradmand et al. 2024, "3D Gaussian
// Splatting as Markov Chain Monte Carlo", as gsplat's MCMCStrategy runs it). Instead of cloning and
// splitting where gradients are large and resetting opacities, the scene is treated as samples of
// the picture's distribution:
// - every `refine_every` steps inside the window, the Gaussians that have gone transparent are
//   moved onto live ones drawn by opacity, and copies drawn the same way grow the scene by at most
//   `growth` until it holds the budget (Trainer::relocate);
// - the loss penalises mean opacity and mean scale, and after every step the nearly transparent
//   Gaussians wander by noise shaped like themselves (TrainOptions::opacity_regularization,
//   scale_regularization, position_noise; the caller sets them from McmcSchedule).
// The SH bands follow the reference schedule.
#include <cstddef>
#include <cstdint>

#include "vksplat/train/strategy.hpp"

namespace vksplat::train {

struct McmcSchedule {
    size_t budget = 0;                   // the most Gaussians the scene grows to
    uint64_t refine_from = 500, refine_until = 25000, refine_every = 100;
    double min_opacity = 0.005;          // at most this: transparent, to be moved
    double growth = 1.05;                // the most a refinement grows the scene by
    // The paper's weights (its defaults for every scene): 0.01, 0.01 and a noise rate of 5e5.
    double opacity_regularization = 0.01;
    double scale_regularization = 0.01;
    double position_noise = 5e5;
    double start_opacity = 0.5;          // the paper's starting opacity (the reference's is 0.1)
    double start_scale = 1.0;            // factor on the starting scales (gsplat's MCMC preset: 0.1)
};

// Copies the schedule's loss and noise terms into the trainer's options.
void use_mcmc_terms(const McmcSchedule& schedule, TrainOptions& options);

struct McmcEvents {
    size_t relocated = 0, added = 0;     // over the run
};

class McmcStrategy final : public Strategy {
public:
    McmcStrategy(const ReferenceSchedule& reference, const McmcSchedule& schedule);
    void before_step(Trainer& trainer, uint64_t iteration) override;
    void after_step(Trainer& trainer, uint64_t iteration) override;
    const McmcEvents& events() const { return events_; }

private:
    ReferenceSchedule reference_;
    McmcSchedule schedule_;
    McmcEvents events_;
};

}  // namespace vksplat::train
