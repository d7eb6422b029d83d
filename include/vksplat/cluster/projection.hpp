#pragma once
// Projection of Gaussians into region maps (GPU): for every Gaussian, the region id at its
// projected centre in one view, or kNoRegion where the centre falls outside the image, the
// Gaussian is culled, or it is occluded there.
//
//   Projector projector(context);
//   auto stats = renderer.render(camera.resized(map.width, map.height), with_stats).stats;
//   std::vector<int32_t> ids = projector.project(stats, map, {});
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vksplat/cluster/region_map.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/render_types.hpp"

namespace vksplat::cluster {

enum class OcclusionRule {
    // A Gaussian is occluded when it lies more than depth_ratio * z_min + depth_offset behind the
    // nearest Gaussian centre z_min that lands in the same pixel (the original rule). Cheap, but it
    // ignores opacity: a faint splat in front hides what is behind it, and a centre alone in its
    // pixel counts as visible even when a large splat covers it.
    depth,
    // Visible where the blend pass gave the Gaussian a weight alpha * T of at least min_weight at
    // the pixel holding its centre (GaussianStats::centre_weight): what the picture shows there.
    blend,
};

// "depth" or "blend"; throws InputError otherwise.
OcclusionRule parse_occlusion_rule(const std::string& name);
std::string to_string(OcclusionRule rule);

struct ProjectionParams {
    OcclusionRule rule = OcclusionRule::depth;
    float depth_ratio = 0.05f;
    float depth_offset = 0.05f;
    float min_weight = 0.05f;
};

class Projector {
public:
    explicit Projector(const gpu::Context& context);
    ~Projector();
    Projector(const Projector&) = delete;
    Projector& operator=(const Projector&) = delete;

    // `stats` from a render (gather_stats) with the map's size. Returns one id per Gaussian.
    std::vector<int32_t> project(const GaussianStats& stats, const RegionMap& map, const ProjectionParams& params);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::cluster
