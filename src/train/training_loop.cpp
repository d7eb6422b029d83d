#include "vksplat/train/training_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "stats/median.hpp"
#include "vksplat/train/skipped_steps.hpp"

namespace vksplat::train {
namespace {

using Clock = std::chrono::steady_clock;

// Progress is reported at most this often (and at the last step).
constexpr double kReportSeconds = 0.5;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Per-pass GPU times of every step, in the order the passes were first recorded.
class StageTimes {
public:
    void add(const std::vector<StageTiming>& stages) {
        for (const auto& stage : stages) {
            auto same =
                std::find_if(times_.begin(), times_.end(), [&](const auto& e) { return e.first == stage.stage; });
            if (same == times_.end()) same = times_.insert(times_.end(), {stage.stage, {}});
            same->second.push_back(stage.milliseconds);
        }
    }
    std::vector<StageTiming> medians() const {
        std::vector<StageTiming> out;
        for (const auto& [label, times] : times_) out.push_back({label, stats::median(times)});
        return out;
    }

private:
    std::vector<std::pair<std::string, std::vector<double>>> times_;
};

}  // namespace

size_t training_view(uint64_t iteration, uint64_t seed, const std::vector<size_t>& views) {
    const uint64_t epoch = iteration / views.size();
    std::vector<size_t> order = views;
    std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + epoch);
    std::shuffle(order.begin(), order.end(), rng);
    return order[iteration % views.size()];
}

LoopResult run_training_loop(Trainer& trainer, Strategy& strategy, const std::vector<Camera>& cameras,
                             const std::vector<size_t>& train_views, const std::map<size_t, Photo>& photos,
                             const LoopOptions& options, const std::function<void(const LoopStatus&)>& progress) {
    LoopResult result;
    StageTimes stages;
    std::vector<double> step_times;
    const auto start = Clock::now();
    auto last_report = start;
    double loss_sum = 0, mse_sum = 0;
    uint64_t since_report = 0;
    // Steps are submitted without waiting (Trainer::submit): their results arrive one step late, or
    // when the strategy, a snapshot or a checkpoint waits for the step in flight.
    const auto take_results = [&] {
        for (const StepResult& step : trainer.take_results()) {
            step_times.push_back(step.gpu_milliseconds);
            stages.add(step.stages);
            loss_sum += step.loss;
            mse_sum += std::pow(10.0, -step.psnr / 10.0);
            ++since_report;
        }
        check_skipped_steps(trainer, options.source);
    };
    trainer.context().reset_peak_device_bytes();
    const SceneChangeTimes changes_before = trainer.scene_change_times();
    const uint64_t first = trainer.iteration();
    while (trainer.iteration() < options.iterations) {
        if (options.stop && options.stop->load()) {
            result.interrupted = true;
            break;
        }
        const uint64_t iteration = trainer.iteration() + 1;  // the reference counts from 1
        strategy.before_step(trainer, iteration);
        const size_t view = training_view(iteration - 1, options.seed, train_views);
        trainer.submit(cameras[view], photos.at(view));
        take_results();

        const auto strategy_start = Clock::now();
        strategy.after_step(trainer, iteration);
        result.strategy_seconds += seconds_since(strategy_start);

        const bool last = iteration == options.iterations;
        if (last) trainer.finish();  // the last report counts the last step
        if (options.snapshot && ((options.snapshot_every > 0 && iteration % options.snapshot_every == 0) || last)) {
            const auto snapshot_start = Clock::now();
            options.snapshot(trainer, iteration);
            result.snapshot_seconds += seconds_since(snapshot_start);
        }
        if (!options.checkpoint.empty() && (iteration % options.checkpoint_every == 0 || last))
            trainer.save_checkpoint(options.checkpoint);
        take_results();  // of a step that the strategy, the snapshot, the checkpoint or the last waited for
        if (progress && since_report > 0 && (last || seconds_since(last_report) >= kReportSeconds)) {
            LoopStatus status;
            status.iteration = iteration;
            status.iterations = options.iterations;
            status.gaussians = trainer.size();
            status.loss = loss_sum / double(since_report);
            status.psnr = -10.0 * std::log10(mse_sum / double(since_report));
            status.seconds = seconds_since(start);
            status.seconds_left = status.seconds / double(iteration - first) * double(options.iterations - iteration);
            progress(status);
            last_report = Clock::now();
            loss_sum = mse_sum = 0;
            since_report = 0;
        }
    }
    trainer.finish();
    take_results();
    result.peak_device_bytes = trainer.context().peak_device_bytes();
    result.scene_changes = trainer.scene_change_times() - changes_before;
    result.seconds = seconds_since(start) - result.snapshot_seconds;
    if (result.interrupted && !options.checkpoint.empty()) trainer.save_checkpoint(options.checkpoint);
    result.iterations = trainer.iteration();
    result.skipped = trainer.skipped_steps();
    result.gpu_ms_per_iteration = stats::median(step_times);
    result.stages = stages.medians();
    return result;
}

}  // namespace vksplat::train
