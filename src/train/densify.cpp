#include "train/densify.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "gpu/kernel.hpp"
#include "shaders/train/densify_gather.kernel.hpp"
#include "shaders/train/reset_opacity.kernel.hpp"
#include "train/parameter_layout.hpp"

namespace vksplat::train {
namespace {

// The reference's split: two new Gaussians sampled from the old one, scales divided by 0.8 * 2.
constexpr int kSplitCount = 2;
constexpr float kSplitShrink = 0.8f * kSplitCount;

// Reads Gaussian i of the geometry block.
struct Geometry {
    const DensifyInputs& in;
    ParameterLayout layout{in.count, 1};

    glm::vec3 scale(size_t i) const {
        const float* s = &in.geometry[layout.log_scales() + 3 * i];
        return {std::exp(s[0]), std::exp(s[1]), std::exp(s[2])};
    }
    // exp of the largest log-scale: the largest scale (exp is monotonic), for one exp, not three.
    float max_scale(size_t i) const {
        const float* s = &in.geometry[layout.log_scales() + 3 * i];
        return std::exp(std::max({s[0], s[1], s[2]}));
    }
    float opacity(size_t i) const { return 1.0f / (1.0f + std::exp(-in.geometry[layout.opacities() + i])); }
    glm::vec3 position(size_t i) const {
        const float* p = &in.geometry[layout.positions() + 3 * i];
        return {p[0], p[1], p[2]};
    }
    glm::mat3 rotation(size_t i) const {
        const float* q = &in.geometry[layout.rotations() + 4 * i];
        return glm::mat3_cast(glm::normalize(glm::quat(q[0], q[1], q[2], q[3])));
    }
};

}  // namespace

void DensifyPlan::add_override(uint32_t source, const glm::vec3& position, const glm::vec3& log_scale,
                               float opacity_logit) {
    sources.push_back(source);
    overrides.insert(overrides.end(), {position.x, position.y, position.z, log_scale.x, log_scale.y, log_scale.z,
                                       opacity_logit});
}

DensifyPlan plan_densify(const DensifyInputs& inputs, const DensifyRules& rules, double scene_extent, uint64_t seed) {
    const size_t n = inputs.count;
    if (inputs.geometry.size() != 11 * n || inputs.sums.size() != kDensifyStride * n)
        throw std::invalid_argument("plan_densify: inputs of the wrong size");
    const Geometry g{inputs};
    const auto sum = [&](size_t i, uint32_t k) { return inputs.sums[i * kDensifyStride + k]; };
    DensifyPlan plan;
    plan.report.before = n;

    // Candidates by their mean NDC gradient over the views that drew them (a threshold of 0 still
    // leaves out those no view drew).
    std::vector<float> grad(n, 0.0f);
    std::vector<uint32_t> candidates;
    for (size_t i = 0; i < n; ++i) {
        const float views = sum(i, 1);
        grad[i] = views > 0 ? sum(i, 0) / views : 0.0f;
        if (views > 0 && grad[i] >= rules.grad_threshold) candidates.push_back(uint32_t(i));
    }
    // Under a cap, growth keeps the best ranked: a clone adds one Gaussian, a split one more than
    // it removes.
    if (rules.max_gaussians > 0) {
        const size_t room = rules.max_gaussians > n ? rules.max_gaussians - n : 0;
        if (room == 0) {
            candidates.clear();
        } else if (candidates.size() > room) {
            std::vector<float> rank(n);
            for (uint32_t i : candidates)
                rank[i] = rules.ranking == DensifyRanking::mean_gradient ? grad[i] : sum(i, 0);
            // The order is total (ties by index), so the `room` best are one set, whichever way
            // they are found: nth_element finds them in linear time, and they are sorted by index
            // below (planning took 0.36-0.41 s of a bonsai 400k run on an H200; 0.47-0.51 s with
            // partial_sort, which also ordered them by rank).
            std::nth_element(candidates.begin(), candidates.begin() + long(room), candidates.end(),
                             [&](uint32_t a, uint32_t b) { return rank[a] > rank[b] || (rank[a] == rank[b] && a < b); });
            candidates.resize(room);
            std::sort(candidates.begin(), candidates.end());
        }
    }
    const float small = float(rules.percent_dense * scene_extent);
    std::vector<uint8_t> split(n, 0), clone(n, 0);
    for (uint32_t i : candidates) (g.max_scale(i) <= small ? clone : split)[i] = 1;

    // Pruned after growing, as the reference prunes (so new Gaussians too): too transparent, or,
    // once asked, larger than max_world_scale x extent (a split sample's scales are the source's
    // divided by `shrink`) or (with max_screen_radius) too large on screen; new Gaussians have no
    // radius yet. The scale is computed only where asked: this runs for every Gaussian at every
    // densification.
    const auto pruned = [&](size_t i, bool is_new, float shrink) {
        if (g.opacity(i) < rules.min_opacity) return true;
        if (!rules.prune_large) return false;
        if (g.max_scale(i) / shrink > float(rules.max_world_scale * scene_extent)) return true;
        return !is_new && rules.max_screen_radius > 0 && sum(i, 2) > rules.max_screen_radius;
    };
    plan.sources.reserve(n);
    for (size_t i = 0; i < n; ++i)
        if (!split[i] && !pruned(i, false, 1.0f)) plan.sources.push_back(uint32_t(i));
    plan.fresh_from = uint32_t(plan.sources.size());
    const size_t survivors = plan.sources.size();
    size_t new_pruned = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!clone[i]) continue;
        if (pruned(i, true, 1.0f)) {
            ++new_pruned;
            continue;
        }
        plan.sources.push_back(uint32_t(i));
        ++plan.report.cloned;
    }
    plan.override_from = uint32_t(plan.sources.size());
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    for (size_t i = 0; i < n; ++i) {
        if (!split[i]) continue;
        ++plan.report.split;
        const glm::vec3 scale = g.scale(i);
        const glm::mat3 rotation = g.rotation(i);
        for (int s = 0; s < kSplitCount; ++s) {
            // Sampled before the prune test, so that a pruned sample does not change the others.
            const glm::vec3 offset = rotation * (scale * glm::vec3(normal(rng), normal(rng), normal(rng)));
            if (pruned(i, true, kSplitShrink)) {
                ++new_pruned;
                continue;
            }
            plan.add_override(uint32_t(i), g.position(i) + offset, glm::log(scale / kSplitShrink),
                              inputs.geometry[g.layout.opacities() + i]);
        }
    }
    plan.report.pruned = n - plan.report.split - survivors + new_pruned;
    plan.report.after = plan.sources.size();
    return plan;
}

struct DensifyPasses::Impl {
    const gpu::Context& context;
    gpu::Kernel<shader::train::DensifyGatherKernel> gather;
    gpu::Kernel<shader::train::ResetOpacityKernel> reset;
    // Every call's commands, each submission waited for. Densification runs every 100 steps, and
    // a command pool, a staging buffer in pinned host memory or a wait per array each cost the
    // host time a GPU spends on several steps; so the stream and the staging are kept, and grow.
    gpu::CommandStream stream;
    gpu::Buffer readback;  // host memory: the inputs plan_densify reads
    gpu::Buffer upload;    // host memory: the plan's sources and overrides
    gpu::Buffer plan;      // the same on the device, which the gather reads

    explicit Impl(const gpu::Context& c) : context(c), gather(c), reset(c), stream(c, 0) {}
};

DensifyPasses::DensifyPasses(const gpu::Context& context) : impl_(std::make_unique<Impl>(context)) {}
DensifyPasses::~DensifyPasses() = default;

DensifyInputs DensifyPasses::download_inputs(const TrainableScene& scene) {
    Impl& d = *impl_;
    const uint32_t n = scene.layout.count;
    const size_t geometry = size_t(n) * 11, sums = size_t(n) * kDensifyStride;
    gpu::reserve(d.readback, d.context, (geometry + sums) * sizeof(float), gpu::MemoryKind::readback,
                 "densification inputs (readback)");
    d.stream.begin();
    d.stream.copy(scene.params, d.readback, geometry * sizeof(float));
    d.stream.copy(scene.densify, d.readback, sums * sizeof(float), 0, geometry * sizeof(float));
    d.stream.barrier_before_host_read();
    d.stream.submit_and_wait();
    const auto* values = static_cast<const float*>(d.readback.mapped());
    return {n, {values, geometry}, {values + geometry, sums}};
}

void DensifyPasses::apply(TrainableScene& scene, const DensifyPlan& plan) {
    Impl& d = *impl_;
    const uint32_t n = scene.layout.count, m = uint32_t(plan.sources.size());
    const ParameterLayout next{m, scene.layout.sh_coefficients};
    // Sums start at zero in the new scene, so the old ones go first; then each array is gathered
    // and the old one freed before the next is made. The most held at once is the old scene's
    // three arrays and one new one, or the new scene whole: never both scenes.
    scene.grads = gpu::Buffer();  // where kept at all: of the old layout
    scene.densify = gpu::Buffer();
    try {
        // The plan in one buffer, sources then overrides; never empty, so that a plan that keeps
        // nothing, or has no splits, still has addresses to pass.
        const VkDeviceSize source_bytes = plan.sources.size() * sizeof(uint32_t);
        const VkDeviceSize plan_bytes = std::max<VkDeviceSize>(source_bytes + plan.overrides.size() * sizeof(float), 4);
        gpu::reserve(d.upload, d.context, plan_bytes, gpu::MemoryKind::upload, "densify plan (staging)");
        gpu::reserve(d.plan, d.context, plan_bytes, gpu::MemoryKind::device, "densify plan");
        auto* staged = static_cast<std::byte*>(d.upload.mapped());
        std::memcpy(staged, plan.sources.data(), source_bytes);
        std::memcpy(staged + source_bytes, plan.overrides.data(), plan.overrides.size() * sizeof(float));
        // Each gather is waited for, so that its old array can go before the next is made.
        const auto gather = [&](gpu::Buffer& array, const char* name, uint32_t zero_from, uint32_t override_from) {
            gpu::Buffer gathered = TrainableScene::allocate_array(d.context, next, name);
            d.stream.dispatch(d.gather,
                              {.old_values = array.address(),
                               .new_values = gathered.address(),
                               .sources = d.plan.address(),
                               .overrides = d.plan.address() + source_bytes,
                               .old_count = n,
                               .new_count = m,
                               .zero_from = zero_from,
                               .override_from = override_from,
                               .sh_floats = next.sh_coefficients * 3},
                              gpu::groups_for(std::max(m, 1u)));
            d.stream.submit_and_wait();
            array = std::move(gathered);
        };
        d.stream.begin();
        d.stream.copy(d.upload, d.plan, plan_bytes);
        d.stream.barrier();
        gather(scene.params, "trained parameters", m, plan.override_from);
        d.stream.begin();
        gather(scene.first_moment, "Adam first moments", plan.fresh_from, m);
        d.stream.begin();
        gather(scene.second_moment, "Adam second moments", plan.fresh_from, m);
        scene.layout = next;
        scene.allocate_sums(d.context);
    } catch (...) {
        scene = TrainableScene();  // part old, part new: nothing of it can be used
        throw;
    }
}

void DensifyPasses::reset_opacity(TrainableScene& scene, double max_opacity) {
    gpu::CommandStream& stream = impl_->stream;
    stream.begin();
    stream.dispatch(impl_->reset,
                    {.params = scene.params.address(),
                     .first_moment = scene.first_moment.address(),
                     .second_moment = scene.second_moment.address(),
                     .count = scene.layout.count,
                     .max_logit = float(std::log(max_opacity / (1.0 - max_opacity)))},
                    gpu::groups_for(scene.layout.count));
    stream.submit_and_wait();
}

uint64_t DensifyPasses::device_bytes() const { return impl_->plan.size(); }

}  // namespace vksplat::train
