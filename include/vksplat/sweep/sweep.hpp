#pragma once
// The pruning sweep: every score method at a list of dropped fractions, each pruned model measured
// on the test views against the photos and against the unpruned render (PSNR, SSIM), timed (GPU
// timestamps, median) and sized; plus the unpruned scene at each SH degree. Writes sweep.csv,
// sh_degrees.csv, totals.npy, SVG charts, comparison sheets and report.html into one folder.
// What `vksplat sweep` does.
//
// The view totals are gathered once over the training views; each method is scored once from them
// and ranked once, and every fraction is a cut of that ranking. The lossless pass (see
// prune/selection.hpp) applies before every method, so fraction 0 is the lossless pass alone and a
// fraction below what it dropped keeps just what it left.
//
// Cluster pruning (jobs/cluster_prune.hpp) joins as the method "cluster" when asked: each Gaussian
// ranks by its cluster's G*, so a kept count takes clusters whole from the best down (the last one
// partly), after the same lossless pass, at the same kept counts as the per-Gaussian methods.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/jobs/cluster_prune.hpp"
#include "vksplat/jobs/prune_recover.hpp"
#include "vksplat/prune/scores.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::sweep {

// What a sweep scores when not told (SweepOptions::methods empty, and `vksplat sweep` without
// --methods): every method but fisher, in the enum's order. Fisher's pass runs on the CPU (bonsai:
// ~1.3 s per view on 2 cores, minutes over its training views), so it is swept only by name.
std::vector<prune::ScoreMethod> default_methods();

struct SweepOptions {
    // Empty: default_methods(), unless `cluster` is set (then cluster pruning alone).
    std::vector<prune::ScoreMethod> methods;
    // Also sweep cluster pruning (after the methods above), with these options; its region views
    // are the sweep's training views unless cluster_options.views names others.
    bool cluster = false;
    jobs::ClusterOptions cluster_options;
    std::vector<double> fractions;             // dropped fractions in [0, 1]; empty: default_sweep_fractions
    std::vector<size_t> test_views;            // empty: default_test_views
    std::vector<size_t> train_views;           // empty: default_train_views
    // At most this many training views, evenly spaced over the list (0: all). Scoring is the
    // sweep's one pass over the training views, so this is what makes a quick run quick.
    size_t max_train_views = 0;
    std::filesystem::path images_dir;          // the photos (required)
    RenderSettings settings;                   // background; the SH degree of every pruned render
    uint64_t seed = 0;                         // for the random method
    // Timing: each of the first `timing_views` test views (0: all) is rendered `timing_warmup`
    // times untimed, then `timing_repetitions` times; a model's ms per frame is the mean over those
    // views of the median frame (see bench/benchmark.hpp). With 0 repetitions no frame is added: it
    // is the median over the test views of their one measuring render's time (for slow devices).
    size_t timing_views = 3;
    int timing_warmup = 1, timing_repetitions = 5;
    // Also render the training views without statistics, to compare with what scoring them cost.
    bool compare_scoring_cost = true;
    // Comparison sheets (photo | unpruned | pruned | error) of every test view, for the best method
    // at those of these fractions that were swept.
    std::vector<double> sheet_fractions{0.5, 0.8, 0.9};
    float sheet_max_error = 0.1f;              // top of the heat maps' colour bar (mean abs error)
    std::string scene_label;                   // names the scene in the report, e.g. its path
    // Re-fit every pruned model (fraction above 0) to the photos for this many iterations, with
    // prune --recover's schedule (jobs/prune_recover.hpp; rounds after the first rank cluster rows
    // by the re-fit's default, blend-mix), and add its row beside the prune-only one as method
    // "<method>+recover". 0: prune only. Each re-fit costs its iterations: on lavapipe, seconds per iteration.
    uint64_t recover_iterations = 0;
    std::optional<int> recover_rounds;  // unset: prune --recover's (jobs::recover_rounds)
    // The scene formats (io::write_scene's names) every model is written in to size it
    // (ModelMeasure::file_bytes), for the charts of PSNR against megabytes per format. SOG is left
    // out by default: its k-means takes about 27 s for 38,605 Gaussians on two CPU cores, more than
    // the rest of a model's measuring; the others take a fraction of a second.
    std::vector<std::string> size_formats{"ply", "compressed-ply", "spz"};
    std::filesystem::path out_dir;
    io::WriteMode mode = io::WriteMode::refuse_existing;
};

// A model's quality on the test views (means over the views) and cost.
struct ModelMeasure {
    size_t gaussians = 0;
    size_t bytes = 0;                  // GaussianCloud::ply_bytes
    // The bytes of the model's file in each of SweepOptions::size_formats, in its order, each
    // written by io::write_scene (prune::scene_file_bytes).
    std::vector<std::pair<std::string, size_t>> file_bytes;
    double psnr = 0, ssim = 0;         // against the photos
    // Against the unpruned render. The PSNR is that of the mean squared error over the views (a mean
    // of per-view PSNRs would be +infinity as soon as one view is identical); +infinity when all are.
    double psnr_vs_unpruned = 0, ssim_vs_unpruned = 0;
    double ms_per_frame = 0;
    // The spread behind ms_per_frame: the fastest and slowest frame of each timed view, averaged
    // over those views; with timing_repetitions 0, the fastest and slowest measuring render.
    double ms_min = 0, ms_max = 0;
    std::vector<double> view_psnr;     // per test view, against the photos
};

// The name of cluster pruning's rows.
inline constexpr const char* kClusterMethod = "cluster";

struct SweepRow {
    std::string method;                // prune::to_string of the method, or kClusterMethod
    double fraction = 0;               // asked for
    double dropped = 0;                // really dropped: 1 - gaussians / unpruned gaussians
    double delta_psnr = 0;             // psnr - the unpruned scene's psnr (both against the photos)
    ModelMeasure measure;
    uint64_t recover_iterations = 0;   // of a "+recover" row
    double recover_seconds = 0;        // its re-fit's wall time (all rounds)
};

// The suffix of re-fitted rows' method names.
inline constexpr const char* kRecoverSuffix = "+recover";

struct ShDegreeMeasure {
    int degree = 0;
    size_t bytes = 0;                  // the unpruned scene stored at this degree
    double psnr = 0, ssim = 0;         // means against the photos
    std::vector<double> view_psnr;     // per test view
};

struct SweepResult {
    std::string device;                // the device's name, as gpu::DeviceInfo gives it
    // A CPU device (lavapipe, llvmpipe): its frame times say little about any GPU's, e.g. pruned
    // models there can time slower than the unpruned one.
    bool device_is_cpu = false;
    SanitizeReport sanitize;
    std::vector<size_t> train_views, test_views;
    std::vector<std::string> test_view_names;
    ModelMeasure unpruned;
    size_t lossless_dropped = 0;
    double scoring_seconds = 0;        // rendering the training views with statistics, summed
    double plain_render_seconds = 0;   // the same views rendered plainly; 0 unless compare_scoring_cost
    double cluster_seconds = 0;        // cluster pruning's stages 1-6; 0 unless options.cluster
    std::vector<SweepRow> rows;        // method-major, fractions in the order given
    std::vector<ShDegreeMeasure> sh_degrees;  // 0 .. the scene's degree
    std::string best_method;
    std::vector<double> sheet_fractions;      // those sheets were made for
    std::vector<std::filesystem::path> sheets;  // relative to out_dir
    // Absolute paths. totals: the view totals (prune/score_files.hpp), so that `vksplat prune
    // --load-scores` can cut any method at any count without rendering the training views again.
    std::filesystem::path csv, sh_csv, totals, report;
};

struct SweepProgress {
    // A stage ("scoring the training views", "sweep", "re-fit of blend at 0.5 dropped", ...) with
    // `done` of `total` steps finished, and the seconds the whole sweep has left: every stage still
    // to come, scoring and re-fits included, each from the time its kind of work has taken so far
    // (re-fit iterations from the re-fits so far). nullopt while some work to come is of a kind not
    // yet timed (before the first re-fit has stepped).
    std::function<void(const std::string& stage, size_t done, size_t total, std::optional<double> seconds_left)> step;
    std::function<void(const SweepRow&)> row;  // each row as it is measured
};

// "0.5", "0.95": a fraction as the files and tables name it (up to 4 decimals, no trailing zeros).
std::string fraction_label(double fraction);

// 0, 0.1, ..., 0.9, 0.95, 0.98.
std::vector<double> default_sweep_fractions();

// `count` of `views`, evenly spaced and including the first; all of them when count is 0 or not
// smaller than their number.
std::vector<size_t> spread_views(const std::vector<size_t>& views, size_t count);

// The prune-only method with the highest PSNR against the photos averaged over the swept fractions
// above 0 (the first in the rows' order on a tie); the rows' first method when no fraction is
// above 0. Re-fitted rows do not compete: the sheets show what pruning alone leaves.
std::string best_method(const std::vector<SweepRow>& rows);

// The sweep in one line for the top of the report: the prune-only or re-fitted row that drops the
// most Gaussians within 1 dB of the unpruned PSNR, with its loss and speed-up, e.g. "best trade:
// blend+recover, 80% fewer Gaussians at -0.42 dB, 2.1x faster (1.20 -> 0.57 ms per frame)"; when
// no row that drops any stays within 1 dB, the one that loses least at the smallest such fraction,
// said so.
std::string summary_line(const SweepResult& result);

// Runs the sweep and writes its files into options.out_dir (created if missing). Refuses, before
// any work, an out_dir that already holds a sweep's files (unless options.mode says overwrite),
// missing photos (with recover_iterations, the training views' too, and re-fit options no round
// can run with), fractions outside [0, 1] and view indices out of range. The folders it makes are
// removed again where they stay empty, also when it is refused or fails.
SweepResult sweep_scene(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                        const SweepOptions& options, const SweepProgress& progress = {});

}  // namespace vksplat::sweep
