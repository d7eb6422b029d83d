#pragma once
// Codebooks for formats that store an index in place of a value (SOG): k-means through OpenCV,
// deterministic (the same input gives the same file), each value or vector labelled with its
// nearest entry.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vksplat::io::detail {

// `size` values sorted ascending, and for each input value the index of the nearest one.
struct ScalarCodebook {
    std::vector<float> values;
    std::vector<uint8_t> labels;
};
// A codebook of `size` (at most 256) entries for `values`, which must be finite: their distinct
// values themselves when there are no more than `size` (exact; the last repeated to fill it), else
// k-means started from the means of `size` equal-count slices of the sorted values.
ScalarCodebook scalar_codebook(std::span<const float> values, int size = 256);

// Rows of `dims` floats and a label per row: the index of its nearest centroid.
struct Palette {
    size_t dims = 0;
    std::vector<float> centroids;  // entries * dims
    std::vector<uint32_t> labels;
    size_t entries() const { return dims == 0 ? 0 : centroids.size() / dims; }
};
// A palette of at most `max_entries` centroids for the rows of `vectors` (rows * dims floats,
// finite): the rows themselves when there are no more than that, else k-means (k-means++ seeds,
// `iterations` Lloyd steps) fitted to at most `fit_rows` of them taken at an even stride, after
// which every row is labelled with its nearest centroid.
Palette vector_palette(std::span<const float> vectors, size_t dims, size_t max_entries, size_t fit_rows,
                       int iterations);

}  // namespace vksplat::io::detail
