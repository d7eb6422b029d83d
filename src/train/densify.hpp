#pragma once
// Adaptive density control of the reference trainer (gaussian_model.py: densify_and_clone,
// densify_and_split, prune, reset_opacity). Gaussians whose projected mean moved the loss most
// (mean NDC gradient norm over the views that drew them, since the last densification) are cloned
// where small and split in two where large; the transparent, and (when asked) the oversized, are
// removed. The host decides from a small download (plan_densify); DensifyPasses moves the
// parameters and Adam's moments on the device by the plan (new Gaussians start with zero
// moments, as the reference's optimizer state does) and resets opacities there
// (shaders/train/densify_gather.comp, reset_opacity.comp; layouts in shaders/train/densify.h).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "gpu/command_stream.hpp"
#include "train/trainable_scene.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::train {

// What plan_densify reads of N Gaussians: the first 11 N floats of the parameter layout
// (positions, log-scales, quaternions, opacity logits) and kDensifyStride sums per Gaussian
// (preprocess_backward's gradient-norm sum, views, largest radius). Views, not copies: from
// DensifyPasses::download_inputs they lie in its readback buffer (valid until its next call),
// since copying 22 MB out at each of a 400k run's events took most of the read-back time.
struct DensifyInputs {
    uint32_t count = 0;
    std::span<const float> geometry;
    std::span<const float> sums;
};

// The new scene: Gaussian j copies old Gaussian sources[j]. Survivors come first in their order,
// then clones, then split samples (as the reference concatenates); from fresh_from on the moments
// are zero; Gaussian j >= override_from takes position, log-scale and opacity logit from
// overrides[7 (j - override_from) ...] (the reference's split samples; MCMC's relocations).
struct DensifyPlan {
    std::vector<uint32_t> sources;
    uint32_t fresh_from = 0, override_from = 0;
    std::vector<float> overrides;
    DensifyReport report;

    // Appends a copy of `source` that takes the given values (override_from must already be set).
    void add_override(uint32_t source, const glm::vec3& position, const glm::vec3& log_scale, float opacity_logit);
};

DensifyPlan plan_densify(const DensifyInputs& inputs, const DensifyRules& rules, double scene_extent, uint64_t seed);

class DensifyPasses {
public:
    explicit DensifyPasses(const gpu::Context& context);
    ~DensifyPasses();
    DensifyPasses(const DensifyPasses&) = delete;
    DensifyPasses& operator=(const DensifyPasses&) = delete;

    // What plan_densify needs of `scene`, read back; valid until the next call.
    DensifyInputs download_inputs(const TrainableScene& scene);
    // Lays `scene` out anew by the plan, from its parameters and moments; its densification sums
    // start at zero, and gradients, if it kept any, are gone. Waits for the device. Holds at most
    // the old scene's parameters and moments and one new array, or the new scene, at once (and
    // the plan's copy on the device, kept for the next call). If it
    // throws (out of device memory), `scene` is left empty: it was part old, part new.
    void apply(TrainableScene& scene, const DensifyPlan& plan);
    // opacity = min(opacity, max_opacity) for every Gaussian, those moments zeroed. Waits.
    void reset_opacity(TrainableScene& scene, double max_opacity);
    // Device memory kept between calls: the last plan's largest copy.
    uint64_t device_bytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::train
