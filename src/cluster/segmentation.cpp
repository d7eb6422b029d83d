// Graph-based segmentation of renders (see segmentation.hpp for why this algorithm).
#include "vksplat/cluster/segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/segmentation.hpp>

namespace vksplat::cluster {

RegionMap segment_render(const std::vector<float>& rgb, const std::vector<float>& alpha, int width, int height,
                         const SegmentationParams& params) {
    const size_t pixels = size_t(width) * size_t(height);
    if (width <= 0 || height <= 0 || rgb.size() != pixels * 3 || alpha.size() != pixels)
        throw std::invalid_argument("segment_render: image sizes disagree");
    cv::Mat image(height, width, CV_8UC3);
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c)  // OpenCV's channel order does not matter to the segmentation
            image.data[p * 3 + c] = uint8_t(std::lround(std::clamp(rgb[p * 3 + c], 0.0f, 1.0f) * 255.0f));
    const int min_size = std::max(1, int(std::lround(params.min_size_fraction * double(pixels))));
    auto segmenter = cv::ximgproc::segmentation::createGraphSegmentation(params.sigma, float(params.k), min_size);
    cv::Mat segments;
    segmenter->processImage(image, segments);

    // A segment that is mostly background (the subject's soft outline joins the background's
    // segment) carries no region, not even on its few pixels above min_alpha.
    const int32_t* segment = segments.ptr<int32_t>();
    const int32_t count = segment[std::max_element(segment, segment + pixels) - segment] + 1;
    std::vector<size_t> total(size_t(count), 0), opaque(size_t(count), 0);
    for (size_t p = 0; p < pixels; ++p) {
        ++total[size_t(segment[p])];
        opaque[size_t(segment[p])] += alpha[p] >= params.min_alpha;
    }
    RegionMap map{width, height, std::vector<int32_t>(pixels)};
    cv::Mat subject(height, width, CV_8U);
    for (size_t p = 0; p < pixels; ++p) {
        const size_t s = size_t(segment[p]);
        map.labels[p] = alpha[p] >= params.min_alpha && 2 * opaque[s] > total[s] ? segment[p] : kNoRegion;
        subject.data[p] = map.labels[p] >= 0 ? 255 : 0;
    }
    // Smoothing blends the subject's outline with the background into thin segments of their own,
    // which are no part of the subject: a segment lying mostly within 2 pixels of the outline
    // carries no region.
    cv::Mat inner;
    cv::erode(subject, inner, cv::getStructuringElement(cv::MORPH_RECT, {5, 5}), {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
    std::vector<size_t> on_outline(size_t(count), 0);
    for (size_t p = 0; p < pixels; ++p)
        if (map.labels[p] >= 0 && !inner.data[p]) ++on_outline[size_t(map.labels[p])];
    for (size_t p = 0; p < pixels; ++p)
        if (map.labels[p] >= 0 && 2 * on_outline[size_t(map.labels[p])] > opaque[size_t(map.labels[p])])
            map.labels[p] = kNoRegion;
    compact_ids(map);
    return map;
}

}  // namespace vksplat::cluster
