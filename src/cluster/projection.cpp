// Projector: uploads one view's projected centres and region map, runs the two projection passes
// (shaders/cluster/cluster_nearest_depth.comp, cluster_project.comp; layouts in
// shaders/cluster/projection.h) and reads back a region id per Gaussian.
#include "vksplat/cluster/projection.hpp"

#include <algorithm>
#include <cstring>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "gpu/transfer.hpp"
#include "shaders/cluster/cluster_nearest_depth.kernel.hpp"
#include "shaders/cluster/cluster_project.kernel.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cluster {
namespace {

// 256 per group in a grid-stride loop, at least 1 and at most 65535 groups.
uint32_t groups_for(uint32_t count) { return std::clamp((count + 255) / 256, 1u, 65535u); }

}  // namespace

OcclusionRule parse_occlusion_rule(const std::string& name) {
    if (name == "depth") return OcclusionRule::depth;
    if (name == "blend") return OcclusionRule::blend;
    throw InputError("occlusion rule '" + name + "'", "expected depth or blend");
}

std::string to_string(OcclusionRule rule) { return rule == OcclusionRule::depth ? "depth" : "blend"; }

struct Projector::Impl {
    const gpu::Context& context;
    gpu::Kernel<shader::cluster::ClusterNearestDepthKernel> nearest_depth;
    gpu::Kernel<shader::cluster::ClusterProjectKernel> project;
    gpu::CommandStream stream;

    explicit Impl(const gpu::Context& c)
        : context(c),
          nearest_depth(c),
          project(c),
          stream(c) {}
};

Projector::Projector(const gpu::Context& context) : impl_(std::make_unique<Impl>(context)) {}
Projector::~Projector() = default;

std::vector<int32_t> Projector::project(const GaussianStats& stats, const RegionMap& map,
                                        const ProjectionParams& params) {
    const size_t n = stats.size();
    const size_t pixels = size_t(map.width) * size_t(map.height);
    if (map.labels.size() != pixels || pixels == 0) throw InputError("region map", "is empty or has a bad size");
    if (n == 0) return {};
    const bool blend = params.rule == OcclusionRule::blend;
    if (blend && stats.centre_weight.size() != n)
        throw InputError("projection", "the blend rule needs statistics with centre weights");
    std::vector<float> centres(n * 4);
    for (size_t i = 0; i < n; ++i) {
        centres[i * 4 + 0] = stats.screen_x[i];
        centres[i * 4 + 1] = stats.screen_y[i];
        centres[i * 4 + 2] = stats.depth[i];
        // Culled Gaussians get 0 in w whatever the rule, so both passes skip them.
        centres[i * 4 + 3] = stats.visible[i] ? (blend ? stats.centre_weight[i] : 1.0f) : 0.0f;
    }
    auto& c = impl_->context;
    const gpu::Buffer centre_buffer = gpu::upload_buffer(c, centres, "projected centres");
    const gpu::Buffer region_buffer = gpu::upload_buffer(c, map.labels, "region map");
    const gpu::Buffer nearest(c, pixels * 4, gpu::MemoryKind::device, "nearest centre depth");
    const gpu::Buffer labels(c, n * 4, gpu::MemoryKind::device, "region id per Gaussian");
    const gpu::Buffer readback(c, n * 4, gpu::MemoryKind::readback, "region id readback");

    auto& stream = impl_->stream;
    const auto count = uint32_t(n), width = uint32_t(map.width), height = uint32_t(map.height);
    stream.begin();
    if (!blend) {
        stream.fill(nearest, 0xffffffffu);  // above every positive float's bits: no centre yet
        stream.barrier();
        stream.dispatch(impl_->nearest_depth,
                        {.centres = centre_buffer.address(),
                         .nearest = nearest.address(),
                         .count = count,
                         .width = width,
                         .height = height},
                        groups_for(count));
        stream.barrier();
    }
    stream.dispatch(impl_->project,
                    {.centres = centre_buffer.address(),
                     .nearest = nearest.address(),
                     .regions = region_buffer.address(),
                     .labels = labels.address(),
                     .count = count,
                     .width = width,
                     .height = height,
                     .rule = blend ? 1u : 0u,
                     .depth_ratio = params.depth_ratio,
                     .depth_offset = params.depth_offset,
                     .min_weight = params.min_weight},
                    groups_for(count));
    stream.barrier();
    stream.copy(labels, readback, n * 4);
    stream.submit_and_wait();
    std::vector<int32_t> out(n);
    std::memcpy(out.data(), readback.mapped(), n * 4);
    return out;
}

}  // namespace vksplat::cluster
