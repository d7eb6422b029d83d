// refit_bench: the re-fit jobs (jobs::finetune_scene, what `vksplat finetune` runs, and with --drop
// jobs::prune_and_recover, what `vksplat prune --ratio R --recover N` runs) on a GPU host
// that has a Vulkan driver and no image codecs. Photos come as <name>.npy (uint8 [H, W, 3], made
// on the host by benchmarks/photos_to_npy.py); quality is PSNR against them on the test views. Prints
// the test PSNR before and after, the time per iteration (GPU median and wall) with its per-pass
// split, the device memory of the re-fit against the renderer's for the same scene, and the bytes
// the model takes as the files a size budget (prune --max-mb) counts, before and after the re-fit.
//
//   refit_bench lego_50.ply --cameras lego/cameras.json --photos npy/ --background 1,1,1 --iters 5000
//   refit_bench lego.ply ... --drop 0.8 --position-lr decay   (80% dropped, prune --recover's ranking (blend-mix) and
//     rounds, their spacing and sampling (jobs::RecoverOptions), iterations by the fraction dropped, as a
//     bare `prune --recover` takes them: jobs::default_recover_iterations)
//   refit_bench lego.ply ... --drop 0.8 --rounds 3 --round-spacing 0 --sample false   (the schedule before)
//   refit_bench lego.ply ... --drop 0.8 --position-lr decay --seconds 60   (a wall-time budget,
//     `prune --recover-seconds 60`), --lr sh_dc=0.5 --lr opacity=0.5 (rates times a factor)
//   refit_bench bonsai.spz ... --drop 0.8 --sh-degree 1   (a size point: the whole cloud at SH degree 1,
//     as `prune --max-mb` may choose it, pruned and re-fitted; its bytes as SPZ and compressed PLY)
//   refit_bench bonsai.spz ... --max-mb 3 --position-lr decay   (`prune --max-mb 3 --recover -o out.spz`:
//     the size search, its choice re-fitted in prune --recover's rounds, the file written and measured)
//   refit_bench bonsai.spz ... --keep keep85.npy --subject --save refit.ply
//     (what `vksplat cluster prune --recover N` re-fits: the Gaussians the mask keeps, the loss of each
//     training view masked to the subject region of the whole scene's render, quality = PSNR inside
//     the test views' regions)
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "vksplat/eval/metrics.hpp"
#include "vksplat/eval/quality.hpp"
#include "vksplat/eval/subject_region.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/prune/accumulate.hpp"
#include "vksplat/prune/sh_precision.hpp"
#include "vksplat/prune/size_budget.hpp"
#include "vksplat/jobs/view_selection.hpp"

#include "npy_photo.hpp"

using namespace vksplat;
using bench::read_npy_photo;

namespace {

// The bytes of `cloud` as the files a size budget measures (prune --max-mb -o x.spz / x.compressed.ply).
void print_file_bytes(const char* what, const GaussianCloud& cloud) {
    std::printf("%s (%zu Gaussians, SH degree %d): %zu bytes as SPZ, %zu as compressed PLY\n", what, cloud.size(),
                cloud.sh_degree, prune::scene_file_bytes(cloud, "spz"), prune::scene_file_bytes(cloud, "compressed-ply"));
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"refit_bench: re-fit a scene to its photos on the GPU and report quality, time and memory"};
    std::string scene_path, cameras_path, photos_dir, device, keep_path, save;
    bool subject_only = false, whole_loss = false;
    std::vector<float> background{0, 0, 0};
    std::optional<uint64_t> iterations;  // unset: 5000, or with --drop by the fraction dropped
    std::optional<double> drop, seconds, max_mb;
    std::optional<int> sh_degree;
    std::vector<std::string> rate_factors;
    const jobs::RecoverOptions recover_defaults;
    std::optional<int> rounds;  // unset: jobs::recover_rounds's
    std::string position_lr;  // unset: what the job measured runs (finetune: final; --drop, --max-mb: decay)
    app.add_option("scene", scene_path)->required();
    app.add_option("--cameras", cameras_path)->required();
    app.add_option("--photos", photos_dir, "folder of <image name>.npy, uint8 [H, W, 3]")->required();
    app.add_option("--background", background)->delimiter(',')->expected(3);
    auto* iters = app.add_option("--iters", iterations, "iterations (default 5000; with --drop: by the fraction dropped)");
    app.add_option("--seconds", seconds, "instead of --iters: a wall-time budget for the whole re-fit")->excludes(iters);
    app.add_option("--lr", rate_factors,
                   "GROUP=F: that group's learning rate times F (sh_dc, sh_rest, opacity, scale, rotation,\n"
                   "position: both ends of its decay; others_final: the others decay to F x by the end); repeatable")
        ->each([](const std::string& text) {
            if (text.find('=') == std::string::npos) throw CLI::ValidationError("--lr", "wants GROUP=F");
        });
    app.add_option("--device", device);
    double ssim_weight = jobs::FinetuneOptions().train.ssim_weight;
    app.add_option("--ssim-weight", ssim_weight, "the loss's lambda: (1 - lambda) L1 + lambda (1 - SSIM); the reference's 0.2");
    uint64_t seed = 0;
    app.add_option("--seed", seed, "the order of the training views and the rounds' samples (FinetuneOptions::seed)");
    auto* drop_option = app.add_option("--drop", drop, "prune this fraction first, ranked by --method (then re-fit)");
    app.add_option("--max-mb", max_mb,
                   "instead of --drop: `prune --max-mb M --recover -o out.spz` (jobs::prune_scene with a size budget;\n"
                   "the file written to --save, else /tmp/refit_bench_max_mb.spz)")
        ->excludes(drop_option);
    app.add_option("--rounds", rounds, "prune-re-fit rounds (with --drop; default: prune --recover's)");
    // prune --recover's default (jobs::score_method_of): a bench that ranked otherwise measured
    // another re-fit than the one users get.
    std::string method(prune::to_string(jobs::RecoverOptions().method));
    app.add_option("--method", method, "the ranking of every round (with --drop; default blend-mix, prune --recover's): blend,\n"
                   "blend-max, blend-mix, volume-blend, fisher (on the CPU)");
    uint64_t round_spacing = recover_defaults.round_spacing;
    app.add_option("--round-spacing", round_spacing, "iterations of each round but the last (0: an equal share)");
    bool sampled = recover_defaults.sampled;
    app.add_option("--sample", sampled,
                   "true: keep a weighted random sample by score in every round, not the best-scored");
    bool deterministic = false, fast_sums = false;
    auto* deterministic_flag = app.add_flag(
        "--deterministic", deterministic,
        "fixed-point gradient sums (finetune --deterministic; the commands' default where the device has 64-bit atomics)");
    app.add_flag("--fast-sums", fast_sums, "float-atomic gradient sums (finetune --fast-sums)")->excludes(deterministic_flag);
    app.add_option("--position-lr", position_lr,
                   "final: the reference's final rate throughout; decay: initial to final (default: final for a\n"
                   "plain re-fit, as finetune; decay with --drop and --max-mb, as prune --recover)")
        ->check(CLI::IsMember({"final", "decay"}));
    app.add_option("--sh-degree", sh_degree, "reduce the whole cloud to this SH degree before pruning and re-fitting")
        ->check(CLI::Range(0, 3));
    std::vector<int> sh_bits;
    app.add_option("--sh-bits", sh_bits, "B1,B2: also measure the re-fitted model with its SH rounded so (prune --sh-bits)")
        ->delimiter(',')
        ->expected(2);
    app.add_option("--keep", keep_path, "uint8 [N] .npy: re-fit only the Gaussians of the scene it marks");
    app.add_flag("--subject", subject_only,
                 "mask the loss and measure inside the subject region (the automatic ball) of the whole scene");
    app.add_flag("--whole-picture-loss", whole_loss, "with --subject: measure inside the region, but let the loss see every pixel");
    app.add_option("--save", save, "write the re-fitted scene here (.ply)");
    CLI11_PARSE(app, argc, argv);
    // Line by line, so that a run stopped at a time limit leaves what it had printed.
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    if (position_lr.empty()) position_lr = drop || max_mb ? "decay" : "final";
    try {
        const GaussianCloud whole = io::read_scene(scene_path);
        GaussianCloud cloud = whole;
        if (!keep_path.empty()) {
            const std::vector<uint8_t> keep = io::read_npy(keep_path).values<uint8_t>();
            if (keep.size() != whole.size()) throw InputError(keep_path, "does not mark every Gaussian of the scene");
            cloud = whole.subset(keep);
        }
        if (sh_degree && *sh_degree < cloud.sh_degree) cloud = cloud.with_sh_degree(*sh_degree);
        const auto cameras = io::read_cameras(cameras_path);
        gpu::Context context(gpu::ContextOptions{device, false, 0});
        jobs::FinetuneOptions options;
        options.seed = seed;
        options.iterations = iterations.value_or(options.iterations);
        options.seconds = seconds;
        for (const std::string& text : rate_factors) {
            const std::string group = text.substr(0, text.find('='));
            const double factor = std::stod(text.substr(text.find('=') + 1));
            train::LearningRates& r = options.train.rates;
            if (group == "sh_dc") r.sh_dc *= factor;
            else if (group == "sh_rest") r.sh_rest *= factor;
            else if (group == "opacity") r.opacity *= factor;
            else if (group == "scale") r.scale *= factor;
            else if (group == "rotation") r.rotation *= factor;
            else if (group == "position") r.position_initial *= factor, r.position_final *= factor;
            else if (group == "others_final") r.others_final *= factor;
            else throw InputError("--lr " + text, "names no learning rate");
            std::printf("learning rate %s x %g\n", group.c_str(), factor);
        }
        options.train.background = {background[0], background[1], background[2]};
        options.train.ssim_weight = ssim_weight;
        if (position_lr == "decay") options.train.position_schedule = train::PositionSchedule::decay;
        // As `vksplat finetune` and `prune --recover` decide (fixed point wherever the device has
        // 64-bit atomics): before, this bench summed with float atomics unless told, which those
        // commands no longer do by default.
        options.train.deterministic = train::fixed_point_sums(context, deterministic, fast_sums);
        const auto test = jobs::default_test_views(cameras);

        std::map<size_t, io::ImageRGB> test_photos;
        for (size_t v : test) test_photos[v] = read_npy_photo(photos_dir, cameras[v]);
        Renderer renderer(context);
        RenderSettings settings;
        settings.background = options.train.background;
        // With --subject-of: each view's subject mask, from the unpruned scene's render of it.
        std::map<size_t, std::vector<uint8_t>> subject;
        if (subject_only) {
            const eval::SubjectBall ball = eval::auto_subject_ball(cameras);
            renderer.set_scene(whole);
            for (size_t v = 0; v < cameras.size(); ++v)
                subject[v] = eval::subject_mask(renderer.render(cameras[v], settings), cameras[v], ball);
            if (!whole_loss) options.loss_masks = [&](size_t v) { return subject.at(v); };
            std::printf("subject: ball at (%.4g, %.4g, %.4g), radius %.4g; loss and quality inside it\n", ball.centre.x,
                        ball.centre.y, ball.centre.z, ball.radius);
            std::printf("loss: %s\n", whole_loss ? "every pixel" : "subject pixels only");
        }
        uint64_t render_bytes = 0;
        const jobs::QualityProbe quality = [&](const GaussianCloud& scene) {
            eval::Quality q;
            renderer.set_scene(scene);
            for (const auto& [v, photo] : test_photos) {
                const RenderOutput out = renderer.render(cameras[v], settings);
                q.psnr.push_back(subject.empty()
                                     ? eval::psnr(out.rgb.data(), photo.rgb.data(), out.width, out.height)
                                     : eval::masked_psnr(out.rgb.data(), photo.rgb.data(), subject.at(v).data(),
                                                         out.width, out.height));
                q.mean_psnr += q.psnr.back() / double(test_photos.size());
                render_bytes = std::max<uint64_t>(render_bytes, renderer.last_frame().device_bytes);
            }
            return q;
        };
        std::printf("%s: %zu Gaussians on %s, gradients summed %s\n", scene_path.c_str(), cloud.size(),
                    context.info().name.c_str(), options.train.deterministic ? "in fixed point" : "with float atomics");
        print_file_bytes("input file", cloud);
        const jobs::PhotoSource photos = [&](const Camera& c) { return read_npy_photo(photos_dir, c); };
        const auto report = [](const train::LoopStatus& s) {
            if (s.iteration % 1000 == 0 || s.iteration == s.iterations)
                std::printf("  iteration %llu: loss %.4f, train PSNR %.2f dB, %.1f s\n",
                            static_cast<unsigned long long>(s.iteration), s.loss, s.psnr, s.seconds);
        };
        // prune --recover's options as the flags set them (--drop and --max-mb).
        jobs::RecoverOptions recover;
        recover.iterations = iterations;
        recover.seconds = seconds;
        recover.rounds = rounds;
        recover.round_spacing = round_spacing;
        recover.sampled = sampled;
        recover.method = prune::parse_score_method(method);
        recover.finetune = options;
        if (max_mb) {
            jobs::PruneOptions prune_options;
            prune_options.method = recover.method;
            prune::SizeBudget size{.max_bytes = static_cast<size_t>(std::llround(*max_mb * 1e6))};
            if (!sh_bits.empty()) size.sh_precision = prune::ShPrecision{sh_bits[0], sh_bits[1]};
            prune_options.selector = size;
            prune_options.test_views = test;
            prune_options.photos = photos;
            prune_options.settings = settings;
            prune_options.recover = recover;
            prune_options.out = save.empty() ? "/tmp/refit_bench_max_mb.spz" : save;
            prune_options.mode = io::WriteMode::overwrite;
            jobs::PruneProgress progress;
            progress.refit = [&](int, const train::LoopStatus& s) { report(s); };
            // Each probe's own time and when it ended, so that a run shows where the job's time goes
            // (the search for each probe's count, its re-fit, its measurement, and what lies between).
            const auto job_start = std::chrono::steady_clock::now();
            progress.probe = [&job_start](const prune::BudgetProbe& p) {
                std::printf("probe: %zu Gaussians, SH %d, %.0f%% of the higher bands dropped, bits %d,%d, %zu bytes: "
                            "%sdrop %.3f dB (%.1f s, at %.1f s)\n",
                            p.kept, p.sh_degree, 100.0 * p.sh_share, p.sh_precision.degree1_bits,
                            p.sh_precision.higher_bits, p.bytes, p.refitted ? "re-fitted (short) " : "", p.drop,
                            p.seconds,
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - job_start).count());
            };
            const jobs::PruneResult pruned = jobs::prune_scene(renderer, cloud, cameras, prune_options, progress);
            const double job_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - job_start).count();
            const prune::BudgetResult& choice = *pruned.budget;
            std::printf("chosen: %zu Gaussians, SH degree %d, %.0f%% of the higher bands dropped per Gaussian, SH bits "
                        "%d,%d (un-refitted drop %.3f dB)\n",
                        choice.kept, choice.sh_degree, 100.0 * choice.sh_share, choice.sh_precision.degree1_bits,
                        choice.sh_precision.higher_bits, choice.drop);
            for (size_t r = 0; r < pruned.recover_rounds.size(); ++r)
                std::printf("%s %zu: %zu Gaussians, %llu iterations, %.1f s\n",
                            pruned.recover_rounds[r].after_fit ? "after the fit, round" : "round", r + 1,
                            pruned.recover_rounds[r].kept,
                            static_cast<unsigned long long>(pruned.recover_rounds[r].iterations),
                            pruned.recover_rounds[r].seconds);
            std::printf("written: %zu Gaussians, %zu bytes (%s)\n", pruned.count_after, pruned.bytes_after,
                        prune_options.out.string().c_str());
            std::printf("test PSNR (%zu views): %.3f -> %.3f dB (%+.3f)\n", test.size(), pruned.before->mean_psnr,
                        pruned.after.mean_psnr, pruned.after.mean_psnr - pruned.before->mean_psnr);
            // The whole job as `prune --max-mb --recover` runs it: scoring, the size search (host
            // work: each count tried writes a file), the short and long re-fits, measuring, writing.
            std::printf("prune job: %.1f s (scoring %.1f s)\n", job_seconds, pruned.scoring_seconds);
            return 0;
        }
        jobs::FinetuneResult result;
        if (!drop) {
            if (!keep_path.empty())
                std::printf("whole scene (%zu Gaussians): test %sPSNR %.3f dB\n", whole.size(),
                            subject.empty() ? "" : "subject ", quality(whole).mean_psnr);
            result = jobs::finetune_scene(context, cloud, cameras, photos, options, quality, report);
            std::printf("test %sPSNR (%zu views): %.3f -> %.3f dB (%+.3f)\n", subject.empty() ? "" : "subject ",
                        test.size(), result.before->mean_psnr, result.after->mean_psnr,
                        result.after->mean_psnr - result.before->mean_psnr);
        } else {
            const auto train = jobs::default_train_views(cameras.size(), test);
            const auto scoring_start = std::chrono::steady_clock::now();
            const prune::ViewTotals totals = prune::accumulate(renderer, cloud, cameras, train, settings, {},
                                                               prune::needs_fisher(recover.method));
            std::printf("scoring %zu views: %.1f s\n", train.size(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - scoring_start).count());
            const std::vector<float> scores = prune::score(cloud, totals, recover.method);
            const prune::KeepMask candidates = prune::lossless_mask(totals);
            const size_t keep = cloud.size() - static_cast<size_t>(std::llround(*drop * double(cloud.size())));
            const double unpruned = quality(cloud).mean_psnr;
            const double pruned =
                quality(cloud.subset(jobs::recover_ranking(scores, candidates, recover, 1).keep_best(keep))).mean_psnr;
            const uint64_t planned = jobs::recover_iterations(recover, cloud.size(), keep);
            const int round_count = jobs::recover_rounds(recover, planned);
            if (seconds)
                std::printf("a budget of %g s over %d rounds\n", *seconds, round_count);
            else
                std::printf("%llu iterations over %d rounds%s\n", static_cast<unsigned long long>(planned), round_count,
                            iterations ? "" : " (by the fraction dropped)");
            const auto recovered = jobs::prune_and_recover(context, renderer, cloud, scores, candidates, keep, cameras,
                                                           photos, recover, quality, [&](int, const train::LoopStatus& s) {
                                                               report(s);
                                                           });
            for (size_t r = 0; r < recovered.rounds.size(); ++r)
                std::printf("round %zu: %zu Gaussians, %llu iterations%s, %.1f s\n", r + 1, recovered.rounds[r].kept,
                            static_cast<unsigned long long>(recovered.rounds[r].refit.iterations),
                            seconds ? (" of " + std::to_string(recovered.rounds[r].refit.planned_iterations) +
                                       " planned by the budget")
                                          .c_str()
                                    : "",
                            recovered.rounds[r].refit.seconds);
            result = recovered.rounds.back().refit;
            result.cloud = recovered.cloud;  // the round's own was moved into the next (prune_and_recover)
            std::printf("test PSNR (%zu views): unpruned %.3f, %.0f%% dropped %.3f (%+.3f), re-fitted %.3f (%+.3f)\n",
                        test.size(), unpruned, 100.0 * *drop, pruned, pruned - unpruned, result.after->mean_psnr,
                        result.after->mean_psnr - unpruned);
        }
        print_file_bytes("re-fitted file", result.cloud);
        // SSIM beside PSNR: a loss weighted otherwise (--ssim-weight) trades one against the other.
        // Measured as prune measures its output (eval::measure_quality against the photos).
        if (subject.empty()) {
            eval::TestViews views;
            views.photos = true;
            for (const auto& [v, photo] : test_photos) {
                views.cameras.push_back(cameras[v]);
                views.targets.push_back(photo.rgb);
            }
            std::printf("test SSIM: unpruned %.4f, re-fitted %.4f\n",
                        eval::measure_quality(renderer, cloud, views, settings, true).mean_ssim,
                        eval::measure_quality(renderer, result.cloud, views, settings, true).mean_ssim);
        }
        if (!sh_bits.empty()) {
            const prune::ShPrecision precision{sh_bits[0], sh_bits[1]};
            const GaussianCloud rounded = prune::with_sh_precision(result.cloud, precision);
            print_file_bytes(("at --sh-bits " + std::to_string(sh_bits[0]) + "," + std::to_string(sh_bits[1])).c_str(),
                             rounded);
            std::printf("test PSNR at --sh-bits %d,%d: %.3f dB\n", sh_bits[0], sh_bits[1], quality(rounded).mean_psnr);
        }
        if (!save.empty()) io::write_scene(result.cloud, save, io::WriteMode::overwrite);
        std::printf("iterations %llu (skipped %llu), wall %.2f s = %.3f ms per iteration, GPU median %.3f ms\n",
                    static_cast<unsigned long long>(result.iterations), static_cast<unsigned long long>(result.skipped),
                    result.seconds, 1e3 * result.seconds / double(result.iterations), result.gpu_ms_per_iteration);
        for (const auto& stage : result.stages) std::printf("    %-20s %.4f ms\n", stage.stage.c_str(), stage.milliseconds);
        std::printf("device memory: re-fit %.1f MB, renderer %.1f MB (%.2fx)\n", double(result.device_bytes) / 1e6,
                    double(render_bytes) / 1e6, double(result.device_bytes) / double(std::max<uint64_t>(render_bytes, 1)));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
