// Projector: uploads one view's projected centres and region map, runs the two projection passes
// and reads back a region id per Gaussian.
#include "vksplat/cluster/projection.hpp"

#include <cstring>

#include "cluster/projection_passes.hpp"
#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/compute_pipeline.hpp"
#include "gpu/transfer.hpp"
#include "shaders/cluster_nearest_depth.spv.h"
#include "shaders/cluster_project.spv.h"
#include "vksplat/error.hpp"

namespace vksplat::cluster {

OcclusionRule parse_occlusion_rule(const std::string& name) {
    if (name == "depth") return OcclusionRule::depth;
    if (name == "blend") return OcclusionRule::blend;
    throw InputError("occlusion rule '" + name + "'", "expected depth or blend");
}

std::string to_string(OcclusionRule rule) { return rule == OcclusionRule::depth ? "depth" : "blend"; }

struct Projector::Impl {
    const gpu::Context& context;
    gpu::ComputePipeline nearest_depth;
    gpu::ComputePipeline project;
    gpu::CommandStream stream;

    explicit Impl(const gpu::Context& c)
        : context(c),
          nearest_depth(c, gpu::spirv_words(cluster_nearest_depth_spv), sizeof(NearestDepthPush), {}, "cluster_nearest_depth"),
          project(c, gpu::spirv_words(cluster_project_spv), sizeof(ProjectPush), {}, "cluster_project"),
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
        record_nearest_depth(stream, impl_->nearest_depth,
                             {centre_buffer.address(), nearest.address(), count, width, height});
        stream.barrier();
    }
    record_project(stream, impl_->project,
                   {centre_buffer.address(), nearest.address(), region_buffer.address(), labels.address(), count,
                    width, height, blend ? 1u : 0u, params.depth_ratio, params.depth_offset, params.min_weight});
    stream.barrier();
    stream.copy(labels, readback, n * 4);
    stream.submit_and_wait();
    std::vector<int32_t> out(n);
    std::memcpy(out.data(), readback.mapped(), n * 4);
    return out;
}

}  // namespace vksplat::cluster
