#include "vksplat/train/skipped_steps.hpp"

#include <cmath>
#include <sstream>

#include "vksplat/error.hpp"

namespace vksplat::train {
namespace {

// Gaussians that sanitising left at a limit: their exponentials overflow float in the backward pass.
size_t at_limits(const GaussianCloud& cloud) {
    size_t count = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        bool limit = std::abs(cloud.opacity_logits[i]) >= kMaxOpacityLogit;
        for (int k = 0; k < 3; ++k) limit = limit || cloud.log_scales[3 * i + k] >= kMaxLogScale;
        count += limit;
    }
    return count;
}

}  // namespace

void check_skipped_steps(const Trainer& trainer, const std::string& what) {
    const uint64_t steps = trainer.iteration(), skipped = trainer.skipped_steps();
    if (steps <= kSkippedGraceSteps || double(skipped) <= kMaxSkippedShare * double(steps)) return;
    const size_t limited = at_limits(trainer.cloud());
    std::ostringstream message;
    message << skipped << " of " << steps << " steps had non-finite gradients and were skipped, so training learns "
            << "nothing; ";
    if (limited > 0)
        message << limited << " Gaussians sit at the sanitiser's limits (log-scale " << kMaxLogScale << ", |opacity "
                << "logit| " << kMaxOpacityLogit << "), where the backward pass overflows: remove or shrink them";
    else
        message << "check the scene's values and the photos";
    message << "; nothing was written";
    throw InputError(what, message.str());
}

}  // namespace vksplat::train
