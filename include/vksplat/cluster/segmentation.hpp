#pragma once
// The built-in segmentation of rendered views into region maps: Felzenszwalb and Huttenlocher's
// graph-based segmentation (OpenCV contrib, cv::ximgproc::segmentation::GraphSegmentation).
//
// Why graph-based rather than SLIC: cluster pruning needs regions that follow the picture's
// edges and whose number adapts to the content, so that a uniformly coloured part stays one
// region. SLIC cuts every view into superpixels of about equal size wherever the edges are,
// splitting plain surfaces into many regions whose borders mean nothing; the semantic constraint
// would then separate Gaussians of one surface. Graph-based segmentation merges across weak
// edges and splits at strong ones, with one scale parameter k.
#include <vector>

#include "vksplat/cluster/region_map.hpp"

namespace vksplat::cluster {

struct SegmentationParams {
    double sigma = 0.8;          // Gaussian pre-smoothing of the picture, pixels
    double k = 500.0;            // scale: larger k gives larger regions
    // Smallest region, as a fraction of the image's pixels (merged into a neighbour below it).
    double min_size_fraction = 0.001;
    // Pixels whose rendered alpha is below this carry no region: the background is not a part of
    // any object, and Gaussians seen only against it are not grouped by it.
    float min_alpha = 0.5f;
};

// Segments one render: rgb (3 floats per pixel in [0, 1]) and alpha, width * height each.
// Throws std::invalid_argument for sizes that disagree.
RegionMap segment_render(const std::vector<float>& rgb, const std::vector<float>& alpha, int width, int height,
                         const SegmentationParams& params = {});

}  // namespace vksplat::cluster
