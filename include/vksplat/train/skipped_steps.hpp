#pragma once
// A run whose steps keep meeting non-finite gradients learns little: the Gaussians they reach do
// not step (StepResult::applied), and the run would end "successfully" with them unchanged.
// Training loops call this after each step and stop with an error instead, once more than
// kMaxSkippedShare of the steps taken (past the first kSkippedGraceSteps, where a single bad view
// weighs too much) were skipped.
#include <cstdint>
#include <string>

#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

inline constexpr double kMaxSkippedShare = 0.05;
inline constexpr uint64_t kSkippedGraceSteps = 20;

// Throws InputError naming `what` (the scene) with the count of skipped steps and the likely
// cause (Gaussians at the sanitiser's scale or opacity limits, counted) when the share is passed.
void check_skipped_steps(const Trainer& trainer, const std::string& what);

}  // namespace vksplat::train
