#include "io/codebook.hpp"

#include <algorithm>
#include <numeric>
#include <opencv2/core.hpp>

namespace vksplat::io::detail {
namespace {

// cv::kmeans draws its k-means++ seeds from the calling thread's cv::theRNG(): a fixed seed makes
// the palette, and so the file, the same on every run; the caller's state is put back afterwards.
class SeededOpenCvRng {
public:
    SeededOpenCvRng() : saved_(cv::theRNG().state) { cv::theRNG().state = 0x5067'5350'4c41'5431ull; }
    ~SeededOpenCvRng() { cv::theRNG().state = saved_; }
    SeededOpenCvRng(const SeededOpenCvRng&) = delete;
    SeededOpenCvRng& operator=(const SeededOpenCvRng&) = delete;

private:
    uint64_t saved_;
};

// The index of the entry of `sorted` nearest to `value` (the lower one on a tie).
uint8_t nearest_sorted(const std::vector<float>& sorted, float value) {
    size_t low = 0, high = sorted.size() - 1;
    while (low < high) {
        const size_t middle = (low + high) / 2;
        if (double(value) <= (double(sorted[middle]) + sorted[middle + 1]) / 2)
            high = middle;
        else
            low = middle + 1;
    }
    return static_cast<uint8_t>(low);
}

}  // namespace

ScalarCodebook scalar_codebook(std::span<const float> values, int size) {
    const size_t n = values.size();
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
    ScalarCodebook book;
    for (const size_t i : order)
        if (book.values.empty() || values[i] != book.values.back()) book.values.push_back(values[i]);
    if (book.values.size() > size_t(size)) {
        // 1-D k-means converges to a poor local optimum from random seeds; equal-count slices of
        // the sorted values start it where the values are, dense regions and tails alike.
        cv::Mat data(static_cast<int>(n), 1, CV_32F), labels(static_cast<int>(n), 1, CV_32S), centers;
        for (size_t rank = 0; rank < n; ++rank) {
            data.at<float>(static_cast<int>(rank)) = values[order[rank]];
            labels.at<int>(static_cast<int>(rank)) = static_cast<int>(rank * size / n);
        }
        cv::kmeans(data, size, labels, cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-9), 1,
                   cv::KMEANS_USE_INITIAL_LABELS, centers);
        book.values.assign(centers.begin<float>(), centers.end<float>());
        std::sort(book.values.begin(), book.values.end());
    }
    if (book.values.empty()) book.values.push_back(0.0f);
    book.values.resize(size_t(size), book.values.back());
    book.labels.resize(n);
    for (size_t i = 0; i < n; ++i) book.labels[i] = nearest_sorted(book.values, values[i]);
    return book;
}

Palette vector_palette(std::span<const float> vectors, size_t dims, size_t max_entries, size_t fit_rows,
                       int iterations) {
    Palette palette;
    palette.dims = dims;
    const size_t rows = dims == 0 ? 0 : vectors.size() / dims;
    if (rows <= max_entries) {
        palette.centroids.assign(vectors.begin(), vectors.end());
        palette.labels.resize(rows);
        std::iota(palette.labels.begin(), palette.labels.end(), uint32_t{0});
        return palette;
    }
    const cv::Mat all(static_cast<int>(rows), static_cast<int>(dims), CV_32F, const_cast<float*>(vectors.data()));
    const size_t stride = (rows + std::max(fit_rows, max_entries) - 1) / std::max(fit_rows, max_entries);
    cv::Mat fit;
    for (size_t row = 0; row < rows; row += stride) fit.push_back(all.row(static_cast<int>(row)));
    cv::Mat centers;
    {
        const SeededOpenCvRng seeded;
        cv::Mat fit_labels;
        cv::kmeans(fit, static_cast<int>(max_entries), fit_labels,
                   cv::TermCriteria(cv::TermCriteria::COUNT, iterations, 0), 1, cv::KMEANS_PP_CENTERS, centers);
    }
    cv::Mat distances, nearest;
    cv::batchDistance(all, centers, distances, CV_32F, nearest, cv::NORM_L2SQR, 1);
    palette.centroids.assign(centers.begin<float>(), centers.end<float>());
    palette.labels.assign(nearest.begin<int>(), nearest.end<int>());
    return palette;
}

}  // namespace vksplat::io::detail
