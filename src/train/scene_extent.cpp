#include "vksplat/train/scene_extent.hpp"

#include <algorithm>

#include "vksplat/error.hpp"
#include "stats/median.hpp"

namespace vksplat::train {
namespace {

constexpr double kOutlierFactor = 10.0;  // distances beyond this many medians are not trusted
constexpr double kExtentMargin = 1.1;    // the reference's getNerfppNorm

}  // namespace

SceneExtent scene_extent(const std::vector<Camera>& cameras) {
    if (cameras.empty()) throw InputError("cameras", "none given: the scene extent needs at least one");
    std::vector<glm::dvec3> centres;
    for (const auto& camera : cameras) centres.push_back(camera.centre());
    // The coordinate-wise median centre and the median distance to it ignore a minority of
    // far-off cameras, which the mean and the maximum would follow.
    glm::dvec3 middle;
    for (int k = 0; k < 3; ++k) {
        std::vector<double> values;
        for (const auto& c : centres) values.push_back(c[k]);
        middle[k] = stats::median(values);
    }
    std::vector<double> distances;
    for (const auto& c : centres) distances.push_back(glm::length(c - middle));
    const double typical = stats::median(distances);

    SceneExtent extent;
    std::vector<glm::dvec3> trusted;
    for (size_t i = 0; i < centres.size(); ++i) {
        if (typical > 0 && distances[i] > kOutlierFactor * typical)
            extent.distrusted.push_back(i);
        else
            trusted.push_back(centres[i]);
    }
    glm::dvec3 mean(0.0);
    for (const auto& c : trusted) mean += c;
    mean /= double(trusted.size());
    double largest = 0;
    for (const auto& c : trusted) largest = std::max(largest, glm::length(c - mean));
    // One camera (or all at one place) has no extent: the reference then divides by nothing
    // useful either; a unit radius keeps the rates at their nominal values.
    extent.radius = largest > 0 ? largest * kExtentMargin : 1.0;
    return extent;
}

}  // namespace vksplat::train
