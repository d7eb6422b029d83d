#include "vksplat/train/trainer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/transfer.hpp"
#include "render/entry_growth.hpp"
#include "render/frame_layout.hpp"
#include "train/checkpoint_file.hpp"
#include "train/densify.hpp"
#include "train/differentiable_renderer.hpp"
#include "train/loss_passes.hpp"
#include "train/relocation.hpp"
#include "train/trainable_scene.hpp"
#include "shaders/train/adam_step.h"
#include "shaders/train/position_noise.kernel.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::train {
namespace {

// torch.optim.Adam's defaults but for epsilon, which the reference sets to 1e-15.
constexpr float kBeta1 = 0.9f, kBeta2 = 0.999f, kEpsilon = 1e-15f;

uint32_t pack_rgba8(float r, float g, float b, uint8_t alpha) {
    const auto byte = [](float v) {
        return static_cast<uint32_t>(std::lround(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f));
    };
    return byte(r) | (byte(g) << 8) | (byte(b) << 16) | (uint32_t(alpha) << 24);
}

double psnr_from_mse(double mse) { return mse > 0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity(); }

using Clock = std::chrono::steady_clock;

// Adds the seconds since `since` to `total` and restarts `since`.
void lap(double& total, Clock::time_point& since) {
    const Clock::time_point now = Clock::now();
    total += std::chrono::duration<double>(now - since).count();
    since = now;
}

}  // namespace

Photo Photo::from_image(const io::ImageRGB& image) {
    return from_image(image, std::vector<uint8_t>(size_t(image.width) * image.height, 255));
}

Photo Photo::from_image(const io::ImageRGB& image, const std::vector<uint8_t>& mask) {
    const size_t pixels = size_t(image.width) * image.height;
    if (image.rgb.size() != pixels * 3 || mask.size() != pixels)
        throw std::invalid_argument("Photo::from_image: image and mask sizes disagree");
    Photo photo{image.width, image.height, std::vector<uint32_t>(pixels)};
    for (size_t i = 0; i < pixels; ++i)
        photo.rgba[i] = pack_rgba8(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2], mask[i] ? 255 : 0);
    return photo;
}

struct Trainer::Impl {
    // What a step needs until it has finished: its photo, its commands (an overflowed step runs
    // again) and what its recording read, as it was when the step was submitted.
    struct Slot {
        Slot(const gpu::Context& context, int index) : stream(context), index(index) {}
        gpu::CommandStream stream;
        int index;  // which readback of the renderer and the loss it copies its results to
        gpu::Buffer photo_upload;
        Camera camera;
        uint64_t step = 0;  // 0-based: Adam's bias correction and the noise's seed count it
        int sh_degree = 0;
        double position_rate = 0;
        double other_rates_factor = 1;
    };

    const gpu::Context& context;
    TrainOptions options;
    SanitizeReport report;
    TrainableScene scene;
    DifferentiableRenderer renderer;
    LossPasses loss;
    // Adam's settings of the step on the device (shaders/train/adam_step.h), written at the start
    // of each step's commands: the queue runs one step at a time, so one buffer serves both slots.
    gpu::Buffer adam_settings;
    gpu::Kernel<shader::train::PositionNoiseKernel> noise;
    DensifyPasses densify;
    // Step N is recorded into slots[N % 2] while step N - 1 runs from the other, and queued behind
    // it, so that the GPU goes from one step to the next without waiting for the host (which took
    // ~0.1 ms a step on an H200). The queue runs one step at a time (each begins with a barrier
    // after everything before it), so the device buffers below and the renderer's are single; only
    // the readbacks are per slot. A step queued behind one that overflowed its tile entries
    // changes nothing (the overflow mark) and is run again after it.
    std::array<Slot, 2> slots;
    Slot* in_flight = nullptr;  // the step submitted last
    std::vector<StepResult> finished;  // results not yet taken (take_results)
    gpu::Buffer photo, pixel_grad;
    uint32_t pixel_capacity = 0;
    uint64_t iteration = 0, skipped = 0;  // iteration: steps submitted
    SceneChangeTimes scene_change_times;
    int sh_degree = 3;
    struct PositionDecay {
        uint64_t from = 0;
        int steps = 0;
    } position_decay;

    Impl(const gpu::Context& c, const TrainOptions& o)
        : context(c),
          options(o),
          renderer(c, o.deterministic ? GradientSums::fixed_point : GradientSums::device_default, o.blend_backward),
          loss(c),
          adam_settings(c, sizeof(shader::train::AdamSettings), gpu::MemoryKind::device, "Adam settings"),
          noise(c),
          densify(c),
          slots{Slot(c, 0), Slot(c, 1)},
          sh_degree(o.sh_degree),
          position_decay{0, o.rates.position_decay_steps} {}

    void ensure_pixels(uint32_t pixels) {
        if (pixels <= pixel_capacity) return;
        for (Slot& slot : slots)
            gpu::replace(slot.photo_upload, context, uint64_t(pixels) * 4, gpu::MemoryKind::upload, "photo (staging)");
        gpu::replace(photo, context, uint64_t(pixels) * 4, gpu::MemoryKind::device, "photo");
        gpu::replace(pixel_grad, context, uint64_t(pixels) * 16, gpu::MemoryKind::device, "pixel gradients");
        pixel_capacity = pixels;
    }

    // How far the decay has gone, 0 to 1.
    double decay_progress() const {
        const double since = double(iteration) - double(std::min(iteration, position_decay.from));
        return std::clamp(since / std::max(position_decay.steps, 1), 0.0, 1.0);
    }

    double position_rate() const {
        const auto& r = options.rates;
        if (options.position_schedule == PositionSchedule::final_rate) return r.position_final * options.scene_extent;
        // The reference's get_expon_lr_func (without its delay, which the reference leaves off).
        const double t = decay_progress();
        return std::exp(std::log(r.position_initial) * (1 - t) + std::log(r.position_final) * t) * options.scene_extent;
    }

    double other_rates_factor() const { return std::pow(options.rates.others_final, decay_progress()); }

    shader::train::AdamSettings adam_settings_of(const Slot& slot) const {
        const auto& r = options.rates;
        const double t = double(slot.step + 1);
        return {.first_moment = scene.first_moment.address(),
                .second_moment = scene.second_moment.address(),
                .lr_position = static_cast<float>(slot.position_rate),
                .lr_scale = static_cast<float>(r.scale * slot.other_rates_factor),
                .lr_rotation = static_cast<float>(r.rotation * slot.other_rates_factor),
                .lr_opacity = static_cast<float>(r.opacity * slot.other_rates_factor),
                .lr_sh_dc = static_cast<float>(r.sh_dc * slot.other_rates_factor),
                .lr_sh_rest = static_cast<float>(r.sh_rest * slot.other_rates_factor),
                .beta1 = kBeta1,
                .beta2 = kBeta2,
                .epsilon = kEpsilon,
                .bias_correction1 = static_cast<float>(1.0 - std::pow(double(kBeta1), t)),
                .bias_correction2 = static_cast<float>(1.0 - std::pow(double(kBeta2), t)),
                // Means over the Gaussians (opacity) and over their 3 axes (scale).
                .opacity_regularization = static_cast<float>(options.opacity_regularization / scene.layout.count),
                .scale_regularization = static_cast<float>(options.scale_regularization / (3.0 * scene.layout.count))};
    }

    ~Impl();
    void submit(const Camera& camera, const Photo& target);
    // `again`: the slot's step is recorded again after an overflow, with nothing queued before it.
    void record(Slot& slot, bool again);
    // Waits for `slot`'s step and keeps its result; `queued` is the step submitted behind it, if any.
    void finish_step(Slot& slot, Slot* queued);
    // Lays the scene out by `plan`. The renderer's frame is idle between steps and about as large
    // as one of the arrays the plan gathers, so it makes room for it (the next step allocates it
    // again): changing the scene then holds no more than a step does.
    void change_scene(const DensifyPlan& plan) {
        renderer.release_frame();
        densify.apply(scene, plan);
    }
    // Densification and relocation alike: waits for the step in flight, reads back what the host
    // plans from, plans (`planner`), and lays the scene out by the plan (`scene_plan` of what was
    // planned; null where it changes nothing), each phase timed into scene_change_times.
    template <class Planner, class ScenePlan>
    auto plan_and_change(Planner&& planner, ScenePlan&& scene_plan) {
        Clock::time_point since = Clock::now();
        finish();
        lap(scene_change_times.wait, since);
        const DensifyInputs inputs = densify.download_inputs(scene);
        lap(scene_change_times.read_back, since);
        auto planned = planner(inputs);
        lap(scene_change_times.plan, since);
        if (const DensifyPlan* plan = scene_plan(planned)) change_scene(*plan);
        lap(scene_change_times.relayout, since);
        return planned;
    }
    // Densification that ran out of device memory leaves no scene (DensifyPasses::apply).
    void check_scene() const {
        if (!scene.params)
            throw std::runtime_error("training cannot go on: densification ran out of device memory and left no scene");
    }
    void finish() {
        check_scene();
        if (!in_flight) return;
        Slot& slot = *in_flight;
        in_flight = nullptr;
        finish_step(slot, nullptr);
    }
    StepResult result_of(const Slot& slot, uint32_t attempts);
    void load_checkpoint(const std::filesystem::path& path);
};

Trainer::Impl::~Impl() {
    // The step's buffers must outlive its commands; what it did no longer matters.
    if (!in_flight) return;
    try {
        in_flight->stream.wait();
    } catch (...) {  // the device is lost: nothing runs any more
    }
}

void Trainer::Impl::submit(const Camera& camera, const Photo& target) {
    check_scene();
    camera.validate();
    if (target.width != camera.width || target.height != camera.height ||
        target.rgba.size() != size_t(target.width) * target.height)
        throw InputError("photo of camera '" + camera.name + "'",
                         "is " + std::to_string(target.width) + "x" + std::to_string(target.height) +
                             " but the camera is " + std::to_string(camera.width) + "x" +
                             std::to_string(camera.height));
    // A step in flight is of the same scene (whatever changes it finishes the step first); of the
    // same image size too, no buffer below grows, and the loss's sums keep their layout.
    if (in_flight && (in_flight->camera.width != camera.width || in_flight->camera.height != camera.height))
        finish();
    const auto [pixels, tiles] = render::image_extent(camera);
    const uint64_t held = context.held_device_bytes();
    Clock::time_point since = Clock::now();
    renderer.ensure(scene.layout.count, pixels, tiles);
    ensure_pixels(pixels);
    // Counted where it allocated: a step that finds its frame in place spends a microsecond here.
    if (context.held_device_bytes() != held) lap(scene_change_times.frame_allocation, since);
    Slot& slot = slots[iteration % 2];
    std::memcpy(slot.photo_upload.mapped(), target.rgba.data(), uint64_t(pixels) * 4);
    slot.camera = camera;
    slot.step = iteration;
    slot.sh_degree = sh_degree;
    slot.position_rate = position_rate();
    slot.other_rates_factor = other_rates_factor();
    record(slot, false);
    slot.stream.submit();
    Slot* previous = in_flight;
    in_flight = &slot;
    ++iteration;
    if (previous) finish_step(*previous, &slot);
}

void Trainer::Impl::record(Slot& slot, bool again) {
    const Camera& camera = slot.camera;
    const uint32_t n = scene.layout.count;
    const uint32_t pixels = render::image_extent(camera).pixels;
    RenderSettings settings;
    settings.background = options.background;
    settings.max_sh_degree = slot.sh_degree;
    const auto params =
        render::make_camera_params(camera, settings, n, scene.sh_degree, false, renderer.entry_capacity());
    gpu::CommandStream& stream = slot.stream;
    stream.begin();
    // The step before may still run: it reads the photo and every buffer this one writes.
    stream.barrier_after_everything();
    const shader::train::AdamSettings adam = adam_settings_of(slot);
    stream.update(adam_settings, &adam, sizeof(adam));
    // The loss is the first to read the photo: its upload runs beside the blend. At the start of
    // the step, the barrier after it held every pass back until the upload had crossed the bus.
    renderer.record_forward(stream, scene, params, [&] { stream.copy(slot.photo_upload, photo, uint64_t(pixels) * 4); });
    loss.record(stream,
                {renderer.color_alpha().address(), photo.address(), pixel_grad.address(), uint32_t(camera.width),
                 uint32_t(camera.height), float(options.ssim_weight)},
                slot.index);
    stream.barrier();
    stream.mark("loss");
    renderer.record_backward(stream, scene, pixel_grad.address(), again, adam_settings.address());
    if (options.position_noise > 0) {
        stream.dispatch(noise,
                        {.params = scene.params.address(),
                         .status = renderer.status_buffer().address(),
                         .count = n,
                         .seed = static_cast<uint32_t>(slot.step * 0x9e3779b9ull),
                         .scale = static_cast<float>(options.position_noise * slot.position_rate)},
                        gpu::groups_for(n));
        stream.barrier();
        stream.mark("position noise");
    }
    renderer.record_readback(stream, slot.index);
    stream.barrier_before_host_read();
}

// A step that overflowed its tile entries (Adam and the passes after it did nothing) runs again,
// synchronously, with grown ones, after the step queued behind it, which its overflow mark kept
// from changing anything, has finished; then the queued step is recorded and queued again.
void Trainer::Impl::finish_step(Slot& slot, Slot* queued) {
    slot.stream.wait();
    uint32_t attempts = 1;
    for (;; ++attempts) {
        renderer.learn_timings(slot.stream, slot.index);
        const uint32_t needed = renderer.entries_needed(slot.index);  // checked even when the frame fits
        if ((renderer.status(slot.index) & kStepOverflowed) == 0) break;
        render::check_frame_attempts(attempts, "view '" + slot.camera.name + "'");
        if (queued) queued->stream.wait();
        renderer.grow_entries(needed);
        record(slot, true);
        slot.stream.submit_and_wait();
    }
    finished.push_back(result_of(slot, attempts));
    if (attempts > 1 && queued) {
        record(*queued, false);
        queued->stream.submit();
    }
}

StepResult Trainer::Impl::result_of(const Slot& slot, uint32_t attempts) {
    StepResult result;
    result.attempts = attempts;
    result.applied = (renderer.status(slot.index) & kStepNonfinite) == 0;
    if (!result.applied) ++skipped;
    const LossValue value = loss.last(slot.index);
    result.loss = value.loss;
    result.l1 = value.l1;
    result.ssim = value.ssim;
    result.psnr = psnr_from_mse(value.mse);
    result.visible = renderer.visible(slot.index);
    result.tile_entries = renderer.entries_needed(slot.index);
    for (const auto& t : slot.stream.stage_times()) {
        result.stages.push_back({t.label, t.milliseconds});
        result.gpu_milliseconds += t.milliseconds;
    }
    return result;
}

Trainer::Trainer(const gpu::Context& context, const GaussianCloud& initial, const TrainOptions& options)
    : impl_(std::make_unique<Impl>(context, options)) {
    GaussianCloud copy = initial;
    impl_->report = sanitize(copy);
    impl_->scene = TrainableScene::upload(context, copy);
}

Trainer::Trainer(const gpu::Context& context, const std::filesystem::path& checkpoint, const TrainOptions& options)
    : impl_(std::make_unique<Impl>(context, options)) {
    impl_->load_checkpoint(checkpoint);
}

Trainer::~Trainer() = default;

bool deterministic_by_default(const gpu::Context& context) { return context.info().int64_atomics; }
bool fixed_point_sums(const gpu::Context& context, bool deterministic, bool fast_sums) {
    return !fast_sums && (deterministic || deterministic_by_default(context));
}

StepResult Trainer::step(const Camera& camera, const Photo& photo) {
    submit(camera, photo);
    impl_->finish();
    StepResult result = std::move(impl_->finished.back());
    impl_->finished.pop_back();
    return result;
}

void Trainer::submit(const Camera& camera, const Photo& photo) { impl_->submit(camera, photo); }
void Trainer::finish() { impl_->finish(); }

std::vector<StepResult> Trainer::take_results() {
    std::vector<StepResult> results;
    results.swap(impl_->finished);
    return results;
}

uint64_t Trainer::iteration() const { return impl_->iteration; }
uint64_t Trainer::skipped_steps() const { return impl_->skipped; }
double Trainer::position_learning_rate() const { return impl_->position_rate(); }
BlendBackward Trainer::blend_backward() const { return impl_->renderer.blend_backward_choice().chosen(); }
void Trainer::set_sh_degree(int degree) { impl_->sh_degree = std::clamp(degree, 0, 3); }
void Trainer::set_position_decay(uint64_t from_iteration, int steps) { impl_->position_decay = {from_iteration, steps}; }

DensifyReport Trainer::densify(const DensifyRules& rules) {
    auto& d = *impl_;
    const auto plan = [&](const DensifyInputs& inputs) {
        return plan_densify(inputs, rules, d.options.scene_extent, d.iteration);
    };
    return d.plan_and_change(plan, [](const DensifyPlan& planned) { return &planned; }).report;
}

RelocationReport Trainer::relocate(const RelocationRules& rules) {
    auto& d = *impl_;
    const auto plan = [&](const DensifyInputs& inputs) { return plan_relocation(inputs, rules, d.iteration); };
    const auto moves = [](const RelocationPlan& planned) {
        return planned.report.relocated + planned.report.added > 0 ? &planned.plan : nullptr;
    };
    return d.plan_and_change(plan, moves).report;
}

size_t Trainer::remove(const std::vector<uint8_t>& keep) {
    auto& d = *impl_;
    if (keep.size() != d.scene.layout.count) throw std::invalid_argument("Trainer::remove: one flag per Gaussian");
    SceneChangeTimes& times = d.scene_change_times;
    Clock::time_point since = Clock::now();
    d.finish();
    lap(times.wait, since);
    DensifyPlan plan;
    for (uint32_t i = 0; i < keep.size(); ++i)
        if (keep[i]) plan.sources.push_back(i);
    plan.fresh_from = plan.override_from = uint32_t(plan.sources.size());
    // Only the sums: the geometry densification plans from is not needed here.
    const std::vector<float> before =
        gpu::read_buffer<float>(d.context, d.scene.densify, uint64_t(d.scene.layout.count) * kDensifyStride);
    lap(times.read_back, since);
    std::vector<float> sums;
    sums.reserve(plan.sources.size() * kDensifyStride);
    for (uint32_t i : plan.sources)
        sums.insert(sums.end(), before.begin() + i * kDensifyStride, before.begin() + (i + 1) * kDensifyStride);
    lap(times.plan, since);
    d.change_scene(plan);
    if (!sums.empty()) d.scene.restore_densify_sums(d.context, sums);
    lap(times.relayout, since);
    return keep.size() - plan.sources.size();
}

// The densification sums carry on: the reference resets opacity without touching them.
void Trainer::reset_opacity(double max_opacity) {
    impl_->finish();
    impl_->densify.reset_opacity(impl_->scene, max_opacity);
}

SceneChangeTimes operator-(const SceneChangeTimes& later, const SceneChangeTimes& earlier) {
    return {later.wait - earlier.wait, later.read_back - earlier.read_back, later.plan - earlier.plan,
            later.relayout - earlier.relayout, later.frame_allocation - earlier.frame_allocation};
}

std::string describe(const SceneChangeTimes& t) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "waiting %.2f s, read back %.2f s, plan %.2f s, re-layout %.2f s; frame allocation %.2f s", t.wait,
                  t.read_back, t.plan, t.relayout, t.frame_allocation);
    return text;
}

const gpu::Context& Trainer::context() const { return impl_->context; }
const SanitizeReport& Trainer::sanitize_report() const { return impl_->report; }
const SceneChangeTimes& Trainer::scene_change_times() const { return impl_->scene_change_times; }
size_t Trainer::size() const { return impl_->scene.layout.count; }
GaussianCloud Trainer::cloud() const {
    impl_->finish();
    return impl_->scene.download(impl_->context);
}

void Trainer::release_frame() {
    impl_->finish();
    impl_->renderer.release_frame();
}

uint64_t Trainer::device_bytes() const {
    const auto& d = *impl_;
    return d.scene.device_bytes() + d.renderer.device_bytes() + d.loss.device_bytes() + d.densify.device_bytes() +
           d.photo.size() + d.pixel_grad.size();
}

void Trainer::save_checkpoint(const std::filesystem::path& path, io::WriteMode mode) const {
    impl_->finish();
    const auto& d = *impl_;
    CheckpointData data;
    data.header = {.gaussians = d.scene.layout.count, .iteration = d.iteration, .owner = d.options.checkpoint_owner};
    data.sh_degree = uint64_t(d.scene.sh_degree);
    data.skipped = d.skipped;
    const uint64_t floats = d.scene.layout.total();
    data.params = gpu::read_buffer<float>(d.context, d.scene.params, floats);
    data.first_moment = gpu::read_buffer<float>(d.context, d.scene.first_moment, floats);
    data.second_moment = gpu::read_buffer<float>(d.context, d.scene.second_moment, floats);
    data.densify_sums =
        gpu::read_buffer<float>(d.context, d.scene.densify, uint64_t(d.scene.layout.count) * kDensifyStride);
    write_checkpoint(path, data, mode);
}

void Trainer::Impl::load_checkpoint(const std::filesystem::path& path) {
    const CheckpointData data = read_checkpoint(path, options.checkpoint_owner);
    const auto count = static_cast<uint32_t>(data.header.gaussians);
    const int degree = int(data.sh_degree);
    const GaussianCloud first = unpack_parameters(data.first_moment, count, degree);
    const GaussianCloud second = unpack_parameters(data.second_moment, count, degree);
    scene = TrainableScene::upload(context, unpack_parameters(data.params, count, degree), &first, &second);
    scene.restore_densify_sums(context, data.densify_sums);
    iteration = data.header.iteration;
    skipped = data.skipped;
    report.input_count = count;
}

}  // namespace vksplat::train
