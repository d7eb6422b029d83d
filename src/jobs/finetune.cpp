// The re-fit job: photos in, Adam steps over random training views, checkpoints, test views
// measured before and after.
#include "vksplat/jobs/finetune.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "jobs/fingerprint.hpp"
#include "jobs/run_checkpoint.hpp"
#include "jobs/training_setup.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::jobs {
io::ImageRGB checked_photo(const PhotoSource& photos, const Camera& camera) {
    io::ImageRGB image = photos(camera);
    if (image.width != camera.width || image.height != camera.height)
        throw InputError("photo of camera '" + camera.name + "'",
                         "is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                             " but the camera is " + std::to_string(camera.width) + "x" +
                             std::to_string(camera.height));
    return image;
}

train::Photo training_photo(const PhotoSource& photos, const Camera& camera, const std::vector<uint8_t>& loss_mask) {
    const io::ImageRGB image = checked_photo(photos, camera);
    if (loss_mask.empty()) return train::Photo::from_image(image);
    if (loss_mask.size() != size_t(camera.width) * size_t(camera.height))
        throw InputError("loss mask of camera '" + camera.name + "'", "is not the camera's size");
    return train::Photo::from_image(image, loss_mask);
}

namespace {

// What a re-fit's checkpoint belongs to: the scene, the cameras and the recipe; --iters may change.
train::CheckpointOwner finetune_owner(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                      const FinetuneOptions& options, const std::vector<size_t>& train_views) {
    return {options.source,
            {{"scene", fingerprint(cloud)},
             {"cameras", fingerprint(cameras)},
             {"training views", list_text(train_views)},
             {"background", colour_text(options.train.background)},
             {"seed", std::to_string(options.seed)},
             {"position rate", options.train.position_schedule == train::PositionSchedule::decay ? "decay" : "final"}}};
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void check_time_budget(const FinetuneOptions& options) {
    if (!options.seconds) return;
    const double seconds = *options.seconds;
    char text[32];
    std::snprintf(text, sizeof(text), "%g", seconds);
    if (!std::isfinite(seconds) || seconds <= 0)
        throw InputError(std::string("--seconds ") + text, "must be a finite number of seconds above 0");
    if (options.resume)
        throw InputError("--resume", "continues a run of a set iteration count: give --iters, not --seconds");
}

// How long a trainer of `cloud` takes to be made and to step, timed on one made for the purpose:
// the trainer the run steps must know its iteration count when it is made (the position rate
// decays over it), so it cannot time itself. Steps are submitted as the run submits them, each
// prepared while the one before runs: a step's time is from one submit's return to the next's.
// The first step, which grows the buffers, is not counted (the second submit waits for it); the
// others stop at 50 or about 2% of `budget`, whichever comes first (at least one).
struct StepTime {
    double make_seconds = 0, step_seconds = 0;
};
StepTime time_steps(const gpu::Context& context, const GaussianCloud& cloud, const train::TrainOptions& options,
                    const std::vector<Camera>& cameras, const std::vector<size_t>& views,
                    const std::map<size_t, train::Photo>& photos, uint64_t seed, double budget) {
    constexpr int kMostSteps = 50;
    constexpr double kShare = 0.02;
    const auto start = Clock::now();
    train::Trainer trainer(context, cloud, options);
    StepTime time{seconds_since(start), 0};
    std::vector<double> steps;
    const auto timed_from = Clock::now();
    auto submitted = timed_from;
    for (uint64_t i = 0; steps.size() < kMostSteps && (steps.empty() || seconds_since(timed_from) < kShare * budget);
         ++i) {
        const size_t view = train::training_view(i, seed, views);
        trainer.submit(cameras[view], photos.at(view));
        if (i > 1) steps.push_back(seconds_since(submitted));
        submitted = Clock::now();
    }
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    time.step_seconds = steps[steps.size() / 2];
    return time;
}

// The re-fit's strategy (train::RefitStrategy: nothing around the steps) that also stops the loop
// at a deadline, passing the caller's stop (Ctrl-C) on: the loop takes one stop flag.
class DeadlineStrategy final : public train::Strategy {
public:
    DeadlineStrategy(Clock::time_point deadline, const std::atomic<bool>* user_stop)
        : deadline_(deadline), user_stop_(user_stop) {}
    void before_step(train::Trainer&, uint64_t) override {}
    void after_step(train::Trainer&, uint64_t) override {
        if (user_stop_ && user_stop_->load()) stop_ = true;
        if (Clock::now() >= deadline_) out_of_time_ = stop_ = true;
    }
    const std::atomic<bool>* stop() const { return &stop_; }
    // The loop stopped because the time was up, not because it was asked to (Ctrl-C).
    bool out_of_time() const { return out_of_time_ && !(user_stop_ && user_stop_->load()); }

private:
    Clock::time_point deadline_;
    const std::atomic<bool>* user_stop_;
    std::atomic<bool> stop_{false};
    bool out_of_time_ = false;
};

}  // namespace

uint64_t planned_iterations(double seconds, double step_seconds) {
    constexpr uint64_t kMost = uint64_t(1) << 30;
    if (!(step_seconds > 0)) return kMost;
    const double steps = std::floor(seconds / step_seconds);
    return steps < 1 ? 1 : steps >= double(kMost) ? kMost : uint64_t(steps);
}

FinetuneResult finetune_scene(const gpu::Context& context, const GaussianCloud& cloud,
                              const std::vector<Camera>& cameras, const PhotoSource& photos,
                              const FinetuneOptions& options, const QualityProbe& quality,
                              const std::function<void(const train::LoopStatus&)>& progress) {
    const auto notice = [&](const std::string& line) {
        if (options.notice) options.notice(line);
    };
    FinetuneResult result;
    ViewSplit split = split_views(cameras, options.test_views, options.train_views);
    result.test_views = std::move(split.test);
    result.train_views = std::move(split.train);
    result.held_out = split.held_out;
    if (result.train_views.empty()) throw InputError("finetune", "no training views");
    check_time_budget(options);

    // Outputs before anything slow: a run must not end in a refusal, nor write over what it read.
    if (!options.out.empty()) {
        io::refuse_input_as_output(options.out, options.inputs);
        io::check_scene_writable(options.out, options.mode);
    }
    train::TrainOptions train_options = options.train;
    train_options.checkpoint_owner = finetune_owner(cloud, cameras, options, result.train_views);
    std::optional<train::CheckpointHeader> resumed;
    if (!options.checkpoint.empty()) {
        RunFiles files{options.checkpoint, options.inputs, {}};
        if (!options.out.empty()) files.outputs.push_back(options.out);
        resumed = check_run_checkpoint(files, train_options.checkpoint_owner, options.resume, options.mode);
    } else if (options.resume) {
        throw InputError("--resume", "no checkpoint to resume from");
    }
    if (!result.held_out) notice(kTestViewsTrainedOnWarning);

    const std::map<size_t, train::Photo> train_photos =
        training_photos(photos, cameras, result.train_views, options.loss_masks);
    if (train_options.scene_extent <= 0) train_options.scene_extent = training_extent(cameras, result.train_views, notice);
    result.scene_extent = train_options.scene_extent;
    if (resumed) notice(resume_notice(*resumed, options.iterations));
    if (quality && !options.resume) {
        GaussianCloud sanitized = cloud;
        sanitize(sanitized);
        result.before = quality(sanitized);
    }

    // A time budget runs from here: the photos are loaded and the scene measured.
    const auto start = Clock::now();
    uint64_t iterations = options.iterations;
    if (options.seconds) {
        const StepTime time = time_steps(context, cloud, train_options, cameras, result.train_views, train_photos,
                                         options.seed, *options.seconds);
        result.planned_iterations = iterations =
            planned_iterations(*options.seconds - seconds_since(start) - time.make_seconds, time.step_seconds);
    }
    if (train_options.position_schedule == train::PositionSchedule::decay)
        train_options.rates.position_decay_steps = static_cast<int>(std::min<uint64_t>(iterations, 1u << 30));
    std::unique_ptr<train::Trainer> trainer =
        options.resume ? std::make_unique<train::Trainer>(context, options.checkpoint, train_options)
                       : std::make_unique<train::Trainer>(context, cloud, train_options);
    result.sanitize = trainer->sanitize_report();

    // Without a budget the deadline lies beyond any run (as does one of more than 30 years).
    const auto budget = std::chrono::duration<double>(std::min(options.seconds.value_or(1e9), 1e9));
    DeadlineStrategy strategy(options.seconds ? start + std::chrono::duration_cast<Clock::duration>(budget)
                                              : Clock::time_point::max(),
                              options.stop);
    // With a time budget the planned count sets only the position rate's decay: the steps timed
    // beforehand ran slower than the run's (bonsai on an H200: planned 5,438 steps in 8.5 s of an
    // 18 s share), so the run goes on at the final rate until the deadline instead of ending early.
    train::LoopOptions loop{.iterations = options.seconds ? uint64_t(1) << 40 : iterations,
                            .seed = options.seed,
                            .checkpoint = options.checkpoint,
                            .checkpoint_every = options.checkpoint_every,
                            .stop = strategy.stop(),
                            .source = options.source};
    static_cast<train::LoopResult&>(result) =
        train::run_training_loop(*trainer, strategy, cameras, result.train_views, train_photos, loop, progress);
    if (strategy.out_of_time()) result.interrupted = false;
    result.device_bytes = trainer->device_bytes();
    result.cloud = trainer->cloud();
    if (result.interrupted) return result;
    if (quality) result.after = quality(result.cloud);
    if (!options.out.empty()) io::write_scene(result.cloud, options.out, options.mode);
    return result;
}

}  // namespace vksplat::jobs
