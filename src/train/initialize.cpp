#include "vksplat/train/initialize.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "scene/point_tree.hpp"

#include "vksplat/error.hpp"
#include "vksplat/reference/sh.hpp"

namespace vksplat::train {
namespace {

constexpr int kNeighbours = 3;            // distCUDA2's k
constexpr float kMinSquaredDistance = 1e-7f;  // its clamp: duplicate points still get a size
constexpr float kInitialOpacity = 0.1f;

}  // namespace

GaussianCloud initial_cloud(const io::SfmPoints& points, int sh_degree) {
    const size_t n = points.size();
    if (n == 0) throw InputError("points", "none to start training from");
    for (size_t i = 0; i < 3 * n; ++i)
        if (!std::isfinite(points.positions[i]))
            throw InputError("point " + std::to_string(i / 3), "has a non-finite coordinate; drop it before training");
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(n);
    const PointSpan view{points.positions};
    const PointTree tree(3, view, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    const float logit = std::log(kInitialOpacity / (1.0f - kInitialOpacity));
    for (size_t i = 0; i < n; ++i) {
        // The point itself comes back first (distance 0), so ask for one more.
        uint32_t index[kNeighbours + 1];
        float squared[kNeighbours + 1];
        const size_t found = tree.knnSearch(&points.positions[3 * i], kNeighbours + 1, index, squared);
        float sum = 0;
        size_t counted = 0;
        for (size_t k = 0; k < found; ++k) {
            if (index[k] == i) continue;
            if (counted == kNeighbours) break;
            sum += squared[k];
            ++counted;
        }
        const float mean = counted > 0 ? sum / float(counted) : kMinSquaredDistance;
        const float log_scale = std::log(std::sqrt(std::max(mean, kMinSquaredDistance)));
        for (int k = 0; k < 3; ++k) {
            cloud.positions[3 * i + k] = points.positions[3 * i + k];
            cloud.log_scales[3 * i + k] = log_scale;
            cloud.sh[i * stride + k] = float((points.colors[3 * i + k] - 0.5) / reference::kShC0);
        }
        cloud.rotations[4 * i] = 1.0f;
        cloud.opacity_logits[i] = logit;
    }
    return cloud;
}

io::SfmPoints random_points(size_t count, float low, float high, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> position(low, high), unit(0.0f, 1.0f);
    io::SfmPoints points;
    for (size_t i = 0; i < count; ++i) {
        for (int k = 0; k < 3; ++k) points.positions.push_back(position(rng));
        // The reference draws SH in [0, 1/255) and converts them to colours.
        for (int k = 0; k < 3; ++k) points.colors.push_back(float(unit(rng) / 255.0 * reference::kShC0 + 0.5));
    }
    return points;
}

}  // namespace vksplat::train
