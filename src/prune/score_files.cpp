// Scores and view totals to and from .npy.
#include "vksplat/prune/score_files.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::prune {
namespace {

constexpr size_t kTotalColumns = 5;  // blend, blend_max, pixels, footprint, views_visible
constexpr size_t kFisherColumns = kTotalColumns + 1;  // and fisher, where it was gathered

std::string shape_text(const std::vector<size_t>& shape) {
    std::string text = "[";
    for (size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
    return text + "]";
}

// A stored count back as an integer; NaN and negative values (never written, but a file may be
// edited) become 0 rather than undefined behaviour.
uint64_t count_from(float value) { return value > 0.0f ? uint64_t(std::min(value, 1e18f)) : 0; }

ViewTotals totals_from_rows(const std::vector<float>& rows, size_t n, size_t columns) {
    ViewTotals totals(n);
    if (columns == kFisherColumns) totals.fisher.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const float* row = &rows[i * columns];
        totals.blend[i] = row[0];
        totals.blend_max[i] = row[1];
        totals.pixels[i] = count_from(row[2]);
        totals.footprint[i] = row[3];
        totals.views_visible[i] = uint32_t(std::min<uint64_t>(count_from(row[4]), UINT32_MAX));
        if (columns == kFisherColumns) totals.fisher[i] = row[5];
    }
    return totals;
}

}  // namespace

void save_scores(const std::vector<float>& scores, const std::filesystem::path& path, io::WriteMode mode) {
    io::write_npy(path, scores.data(), {scores.size()}, mode);
}

void save_totals(const ViewTotals& totals, const std::filesystem::path& path, io::WriteMode mode) {
    const size_t columns = totals.fisher.empty() ? kTotalColumns : kFisherColumns;
    std::vector<float> rows(totals.size() * columns);
    for (size_t i = 0; i < totals.size(); ++i) {
        float* row = &rows[i * columns];
        row[0] = float(totals.blend[i]);
        row[1] = totals.blend_max[i];
        row[2] = float(totals.pixels[i]);
        row[3] = float(totals.footprint[i]);
        row[4] = float(totals.views_visible[i]);
        if (columns == kFisherColumns) row[5] = totals.fisher[i];
    }
    io::write_npy(path, rows.data(), {totals.size(), columns}, mode);
}

ScoreFile load_score_file(const std::filesystem::path& path) {
    const io::NpyArray array = io::read_npy(path);
    const std::vector<float> values = array.values<float>();
    ScoreFile file;
    if (array.shape.size() == 1)
        file.scores = values;
    else if (array.shape.size() == 2 && (array.shape[1] == kTotalColumns || array.shape[1] == kFisherColumns))
        file.totals = totals_from_rows(values, array.shape[0], array.shape[1]);
    else
        throw InputError(path.string(), "has shape " + shape_text(array.shape) +
                                            "; expected scores [N] or view totals [N, 5] (or [N, 6] with fisher)");
    return file;
}

}  // namespace vksplat::prune
