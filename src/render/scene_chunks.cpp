#include "render/scene_chunks.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#include "vksplat/constants.hpp"

namespace vksplat::render {

std::vector<uint32_t> depth_order(const HostScene& host, const CameraParams& params) {
    const float* row = params.view_row2.v;
    const float near_cut = static_cast<float>(constants::kNearPlane) * 0.5f;
    std::vector<uint64_t> keys;
    keys.reserve(host.count);
    for (uint32_t i = 0; i < host.count; ++i) {
        const float* p = &host.params[size_t(i) * 12];
        const float depth = row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3];
        // Positive floats order as their bits do; the rest are culled (and so is NaN, by !(>)).
        if (!(depth > near_cut)) continue;
        keys.push_back(uint64_t(std::bit_cast<uint32_t>(depth)) << 32 | i);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<uint32_t> order(keys.size());
    for (size_t k = 0; k < keys.size(); ++k) order[k] = static_cast<uint32_t>(keys[k]);
    return order;
}

SceneChunks::SceneChunks(const gpu::Context& context, uint32_t capacity_, int sh_degree, bool half_sh)
    : capacity(std::max(capacity_, 1u)) {
    const uint64_t sh_bytes = GpuScene::sh_bytes_for(capacity, sh_degree, half_sh);
    device.sh_degree = sh_degree;
    device.half_sh = half_sh;
    device.params = gpu::Buffer(context, uint64_t(capacity) * GpuScene::kParamBytesPerGaussian, gpu::MemoryKind::device, "Gaussian parameters (chunk)");
    device.sh = gpu::Buffer(context, sh_bytes, gpu::MemoryKind::device, "spherical harmonics (chunk)");
    staging_params = gpu::Buffer(context, device.params.size(), gpu::MemoryKind::upload, "chunk parameters (staging)");
    staging_sh = gpu::Buffer(context, sh_bytes, gpu::MemoryKind::upload, "chunk SH (staging)");
}

void SceneChunks::stage(const HostScene& host, std::span<const uint32_t> indices) {
    device.count = static_cast<uint32_t>(indices.size());
    auto* params = static_cast<float*>(staging_params.mapped());
    const uint32_t stride = host.sh_floats();
    std::vector<float> sh(size_t(indices.size()) * stride);
    for (size_t k = 0; k < indices.size(); ++k) {
        std::memcpy(params + k * 12, &host.params[size_t(indices[k]) * 12], 12 * sizeof(float));
        std::memcpy(sh.data() + k * stride, &host.sh[size_t(indices[k]) * stride], stride * sizeof(float));
    }
    if (device.half_sh) {
        const auto words = pack_halves(sh);
        std::memcpy(staging_sh.mapped(), words.data(), words.size() * sizeof(uint32_t));
    } else if (!sh.empty()) {  // an empty chunk's vector has no storage to copy from
        std::memcpy(staging_sh.mapped(), sh.data(), sh.size() * sizeof(float));
    }
}

void SceneChunks::record_upload(gpu::CommandStream& stream) const {
    const uint64_t sh_bytes = GpuScene::sh_bytes_for(device.count, device.sh_degree, device.half_sh);
    if (device.count > 0)
        stream.copy(staging_params, device.params, uint64_t(device.count) * GpuScene::kParamBytesPerGaussian);
    if (sh_bytes > 0) stream.copy(staging_sh, device.sh, sh_bytes);
    stream.barrier();
}

}  // namespace vksplat::render
