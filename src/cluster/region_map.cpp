// Region maps: compaction, mask stacks, and the file forms they are read from and written to.
#include "vksplat/cluster/region_map.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include <opencv2/imgcodecs.hpp>

#include "vksplat/error.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::cluster {

size_t RegionMap::region_count() const {
    std::vector<int32_t> ids;
    for (int32_t id : labels)
        if (id >= 0) ids.push_back(id);
    std::sort(ids.begin(), ids.end());
    return size_t(std::unique(ids.begin(), ids.end()) - ids.begin());
}

size_t RegionMap::labelled_pixels() const {
    return size_t(std::count_if(labels.begin(), labels.end(), [](int32_t id) { return id >= 0; }));
}

void compact_ids(RegionMap& map) {
    std::unordered_map<int32_t, int32_t> renumbered;
    for (int32_t& id : map.labels) {
        if (id < 0) {
            id = kNoRegion;
            continue;
        }
        const auto [it, inserted] = renumbered.try_emplace(id, int32_t(renumbered.size()));
        id = it->second;
    }
}

RegionMap combine_masks(const std::vector<std::vector<uint8_t>>& masks, int width, int height) {
    const size_t pixels = size_t(width) * size_t(height);
    std::vector<size_t> area(masks.size());
    for (size_t k = 0; k < masks.size(); ++k) {
        if (masks[k].size() != pixels)
            throw InputError("mask " + std::to_string(k), "has " + std::to_string(masks[k].size()) +
                                                               " pixels, expected " + std::to_string(pixels));
        area[k] = size_t(std::count_if(masks[k].begin(), masks[k].end(), [](uint8_t v) { return v != 0; }));
    }
    std::vector<size_t> order(masks.size());
    std::iota(order.begin(), order.end(), size_t(0));
    // Largest first, so that smaller masks, painted later, win where they overlap.
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return area[a] > area[b]; });
    RegionMap map{width, height, std::vector<int32_t>(pixels, kNoRegion)};
    for (size_t k : order)
        for (size_t p = 0; p < pixels; ++p)
            if (masks[k][p]) map.labels[p] = int32_t(k);
    return map;
}

namespace {

RegionMap from_npy(const std::filesystem::path& path) {
    const io::NpyArray array = io::read_npy(path);
    if (array.shape.size() == 2 && array.dtype == io::NpyDtype::int32)
        return {int(array.shape[1]), int(array.shape[0]), array.values<int32_t>()};
    if (array.shape.size() == 2 && array.dtype == io::NpyDtype::int16) {
        const auto values = array.values<int16_t>();
        return {int(array.shape[1]), int(array.shape[0]), std::vector<int32_t>(values.begin(), values.end())};
    }
    if (array.shape.size() == 3 && array.dtype == io::NpyDtype::uint8) {
        const size_t pixels = array.shape[1] * array.shape[2];
        const auto values = array.values<uint8_t>();
        std::vector<std::vector<uint8_t>> masks(array.shape[0]);
        for (size_t k = 0; k < masks.size(); ++k)
            masks[k].assign(values.begin() + ptrdiff_t(k * pixels), values.begin() + ptrdiff_t((k + 1) * pixels));
        return combine_masks(masks, int(array.shape[2]), int(array.shape[1]));
    }
    throw InputError(path.string(), "expected a region map as int32 or int16 [H, W], or masks as uint8 [K, H, W]; "
                                    "found " + to_string(array.dtype) + " with " +
                                        std::to_string(array.shape.size()) + " dimensions");
}

RegionMap from_label_image(const std::filesystem::path& path) {
    const cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (image.empty()) throw InputError(path.string(), "cannot be read as an image");
    if (image.channels() != 1 || (image.depth() != CV_16U && image.depth() != CV_8U))
        throw InputError(path.string(), "a label image must be one channel of 8 or 16 bits");
    RegionMap map{image.cols, image.rows, std::vector<int32_t>(size_t(image.cols) * image.rows)};
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x) {
            const int value = image.depth() == CV_16U ? image.at<uint16_t>(y, x) : image.at<uint8_t>(y, x);
            map.labels[size_t(y) * image.cols + x] = value == 0 ? kNoRegion : value;  // 0: no region
        }
    return map;
}

}  // namespace

RegionMap read_region_map(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path)) throw InputError(path.string(), "no such file");
    RegionMap map = path.extension() == ".npy" ? from_npy(path) : from_label_image(path);
    if (map.width <= 0 || map.height <= 0) throw InputError(path.string(), "region map is empty");
    compact_ids(map);
    return map;
}

void write_region_map(const std::filesystem::path& path, const RegionMap& map, io::WriteMode mode) {
    io::write_npy(path, map.labels.data(), {size_t(map.height), size_t(map.width)}, mode);
}

}  // namespace vksplat::cluster
