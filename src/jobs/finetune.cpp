// The re-fit job: photos in, Adam steps over random training views, checkpoints, test views
// measured before and after.
#include "vksplat/jobs/finetune.hpp"

#include <algorithm>
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

}  // namespace

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
    if (train_options.position_schedule == train::PositionSchedule::decay)
        train_options.rates.position_decay_steps = static_cast<int>(std::min<uint64_t>(options.iterations, 1u << 30));
    std::unique_ptr<train::Trainer> trainer =
        options.resume ? std::make_unique<train::Trainer>(context, options.checkpoint, train_options)
                       : std::make_unique<train::Trainer>(context, cloud, train_options);
    result.sanitize = trainer->sanitize_report();
    if (quality && !options.resume) result.before = quality(trainer->cloud());

    train::RefitStrategy strategy;
    train::LoopOptions loop{.iterations = options.iterations,
                            .seed = options.seed,
                            .checkpoint = options.checkpoint,
                            .checkpoint_every = options.checkpoint_every,
                            .stop = options.stop,
                            .source = options.source};
    static_cast<train::LoopResult&>(result) =
        train::run_training_loop(*trainer, strategy, cameras, result.train_views, train_photos, loop, progress);
    result.device_bytes = trainer->device_bytes();
    result.cloud = trainer->cloud();
    if (result.interrupted) return result;
    if (quality) result.after = quality(result.cloud);
    if (!options.out.empty()) io::write_scene(result.cloud, options.out, options.mode);
    return result;
}

}  // namespace vksplat::jobs
