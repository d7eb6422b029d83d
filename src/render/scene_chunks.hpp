#pragma once
// Frames larger than the memory budget: the scene stays in host memory (HostScene) and each
// frame uploads it one depth-ordered chunk at a time into device buffers sized for one chunk.
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "render/frame_layout.hpp"
#include "render/gpu_scene.hpp"

namespace vksplat::render {

// The Gaussians a view can draw, front to back in the order the GPU's depth sort puts them:
// by view-space depth as float bits (computed like preprocess.comp: the third row of the view
// matrix dotted with the position, plus the translation, in float), ties by index (the sort is
// stable over index-ordered keys). Chunks are consecutive runs of this order, so a chunk boundary
// between equal depths keeps the lower index in the earlier chunk, as one whole-scene sort would.
// Only where the host's and the GPU's float rounding disagree about two depths within an ulp or
// so of each other, on either side of a boundary, can two splats swap (a rounding-level change).
// Gaussians well behind the near plane (depth below half of it) are left out: preprocess culls
// them anyway, and float rounding cannot move a depth that far.
std::vector<uint32_t> depth_order(const HostScene& host, const CameraParams& params);

struct SceneChunks {
    GpuScene device;         // capacity Gaussians; count is the staged chunk's
    gpu::Buffer staging_params, staging_sh;
    uint32_t capacity = 0;

    SceneChunks(const gpu::Context& context, uint32_t capacity, int sh_degree, bool half_sh);
    // Copies the Gaussians `indices` (ascending, so that the GPU's index tie-break agrees with
    // the host's) into the staging buffers, in that order.
    void stage(const HostScene& host, std::span<const uint32_t> indices);
    // Records the copy of the staged chunk into the device buffers, and a barrier after it.
    void record_upload(gpu::CommandStream& stream) const;
};

}  // namespace vksplat::render
