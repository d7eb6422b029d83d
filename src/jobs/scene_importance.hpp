#pragma once
// How much each Gaussian of a scene in training is worth keeping, for the strategies that grow a
// scene past its budget and settle it back (train::BudgetStrategy): the budget recipe of `train`
// and the regrowth of `prune --recover`'s last round score the trainer's current Gaussians alike.
#include <cstdint>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/budget_strategy.hpp"

namespace vksplat::jobs {

// prune::score by `method` over the `views` of `cameras`, rendered with `settings` on the scene it
// is given, each time by a renderer of its own so that its device memory is held only while it
// scores (`seed` draws the random method's). With `sampled`: prune::sampling_keys of the scores
// instead (a weighted sample is kept, not the best), seeded by `seed` and the scene's count, which
// differs between settlings and is the same in a resumed run.
train::Importance importance_over(const gpu::Context& context, std::vector<Camera> cameras, std::vector<size_t> views,
                                  const RenderSettings& settings, prune::ScoreMethod method, uint64_t seed,
                                  bool sampled);

}  // namespace vksplat::jobs
