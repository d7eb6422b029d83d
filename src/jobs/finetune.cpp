// The re-fit job: photos in, Adam steps over random training views, checkpoints, test views
// measured before and after.
#include "vksplat/jobs/finetune.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

#include "jobs/fingerprint.hpp"
#include "jobs/run_checkpoint.hpp"
#include "stats/median.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/view_selection.hpp"
#include "vksplat/train/scene_extent.hpp"
#include "vksplat/train/skipped_steps.hpp"

namespace vksplat::jobs {
namespace {

using Clock = std::chrono::steady_clock;

// Progress is reported at most this often (and at the last step).
constexpr double kReportSeconds = 0.5;

}  // namespace

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

}  // namespace

FinetuneResult finetune_scene(const gpu::Context& context, const GaussianCloud& cloud,
                              const std::vector<Camera>& cameras, const PhotoSource& photos,
                              const FinetuneOptions& options, const QualityProbe& quality,
                              const std::function<void(const FinetuneStatus&)>& progress) {
    const auto notice = [&](const std::string& line) {
        if (options.notice) options.notice(line);
    };
    FinetuneResult result;
    ViewSplit split = split_views(cameras, options.test_views, options.train_views);
    result.test_views = std::move(split.test);
    result.train_views = std::move(split.train);
    result.held_out = split.held_out;
    if (result.train_views.empty()) throw InputError("finetune", "no training views");

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
    if (!result.held_out)
        notice(kTestViewsTrainedOnWarning);

    // Every photo is read and checked before the first step: a bad one found late would waste the run.
    std::map<size_t, train::Photo> train_photos;
    for (size_t view : result.train_views) {
        train_photos.emplace(view, training_photo(photos, cameras[view],
                                                  options.loss_masks ? options.loss_masks(view) : std::vector<uint8_t>{}));
    }

    if (train_options.scene_extent <= 0) {
        std::vector<Camera> train_cameras;
        for (size_t view : result.train_views) train_cameras.push_back(cameras[view]);
        const train::SceneExtent extent = train::scene_extent(train_cameras);
        train_options.scene_extent = extent.radius;
        for (size_t i : extent.distrusted)
            notice("warning: camera '" + cameras[result.train_views[i]].name +
                   "' lies far from the others; left out of the scene extent");
    }
    result.scene_extent = train_options.scene_extent;
    if (resumed) notice(resume_notice(*resumed, options.iterations));
    if (train_options.position_schedule == train::PositionSchedule::decay)
        train_options.rates.position_decay_steps = static_cast<int>(std::min<uint64_t>(options.iterations, 1u << 30));
    std::unique_ptr<train::Trainer> trainer =
        options.resume ? std::make_unique<train::Trainer>(context, options.checkpoint, train_options)
                       : std::make_unique<train::Trainer>(context, cloud, train_options);
    result.sanitize = trainer->sanitize_report();
    if (quality && !options.resume) result.before = quality(trainer->cloud());

    std::vector<std::pair<std::string, std::vector<double>>> stage_times;  // in recording order
    std::vector<double> step_times;
    const auto start = Clock::now();
    auto last_report = start;
    double loss_sum = 0, mse_sum = 0;
    uint64_t since_report = 0;
    const uint64_t first = trainer->iteration();
    while (trainer->iteration() < options.iterations) {
        if (options.stop && options.stop->load()) {
            result.interrupted = true;
            break;
        }
        const uint64_t iteration = trainer->iteration();
        const size_t view = training_view(iteration, options.seed, result.train_views);
        const train::StepResult step = trainer->step(cameras[view], train_photos.at(view));
        step_times.push_back(step.gpu_milliseconds);
        for (const auto& stage : step.stages) {
            auto same = std::find_if(stage_times.begin(), stage_times.end(),
                                     [&](const auto& entry) { return entry.first == stage.stage; });
            if (same == stage_times.end()) same = stage_times.insert(stage_times.end(), {stage.stage, {}});
            same->second.push_back(stage.milliseconds);
        }
        loss_sum += step.loss;
        mse_sum += std::pow(10.0, -step.psnr / 10.0);
        ++since_report;
        train::check_skipped_steps(*trainer, options.source);
        const bool last = trainer->iteration() == options.iterations;
        if (!options.checkpoint.empty() && (trainer->iteration() % options.checkpoint_every == 0 || last))
            trainer->save_checkpoint(options.checkpoint);
        const auto now = Clock::now();
        if (progress && (last || std::chrono::duration<double>(now - last_report).count() >= kReportSeconds)) {
            FinetuneStatus status;
            status.iteration = trainer->iteration();
            status.iterations = options.iterations;
            status.loss = loss_sum / double(since_report);
            status.psnr = -10.0 * std::log10(mse_sum / double(since_report));
            status.seconds = std::chrono::duration<double>(now - start).count();
            const double per_step = status.seconds / double(trainer->iteration() - first);
            status.seconds_left = per_step * double(options.iterations - trainer->iteration());
            status.gaussians = trainer->size();
            progress(status);
            last_report = now;
            loss_sum = mse_sum = 0;
            since_report = 0;
        }
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (result.interrupted && !options.checkpoint.empty()) trainer->save_checkpoint(options.checkpoint);
    result.iterations = trainer->iteration();
    result.skipped = trainer->skipped_steps();
    result.gpu_ms_per_iteration = stats::median(step_times);
    for (const auto& [label, times] : stage_times) result.stages.push_back({label, stats::median(times)});
    result.device_bytes = trainer->device_bytes();
    result.cloud = trainer->cloud();
    if (result.interrupted) return result;
    if (quality) result.after = quality(result.cloud);
    if (!options.out.empty()) io::write_scene(result.cloud, options.out, options.mode);
    return result;
}

}  // namespace vksplat::jobs
