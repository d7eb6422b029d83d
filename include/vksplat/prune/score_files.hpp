#pragma once
// Scores and view totals as .npy files, so that a selection can be redone without rendering again
// and Python users can inspect them with one call to numpy.load.
//   scores: float32 [N], one method's scores (save_scores).
//   totals: float32 [N, 5], one row per Gaussian with the columns blend, blend_max, pixels,
//           footprint, views_visible (save_totals); every method can be scored from them, and the
//           lossless pass reads their pixel counts. float32 keeps the counts exact up to 2^24 and,
//           what the lossless pass needs, zero and non-zero apart. ViewTotals::views is not stored.
//           Totals that hold fisher scores (ViewTotals::fisher) have it as a sixth column: [N, 6].
#include <filesystem>
#include <optional>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/prune/accumulate.hpp"

namespace vksplat::prune {

void save_scores(const std::vector<float>& scores, const std::filesystem::path& path,
                 io::WriteMode mode = io::WriteMode::refuse_existing);
void save_totals(const ViewTotals& totals, const std::filesystem::path& path,
                 io::WriteMode mode = io::WriteMode::refuse_existing);

// What a file written by either holds: scores, or totals.
struct ScoreFile {
    std::optional<std::vector<float>> scores;
    std::optional<ViewTotals> totals;
    size_t size() const { return scores ? scores->size() : totals->size(); }
};
// Throws InputError naming the file for another dtype or shape.
ScoreFile load_score_file(const std::filesystem::path& path);

}  // namespace vksplat::prune
