#include "render/gpu_scene.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "gpu/transfer.hpp"
#include "vksplat/error.hpp"

namespace vksplat::render {

// Values beyond the half range are clamped to it rather than becoming infinities, which would
// turn into NaN colours.
std::vector<uint32_t> pack_halves(std::span<const float> values) {
    constexpr float kHalfMax = 65504.0f;
    std::vector<uint32_t> words((values.size() + 1) / 2, 0);
    for (size_t i = 0; i < values.size(); ++i)
        words[i / 2] |= uint32_t(glm::packHalf1x16(std::clamp(values[i], -kHalfMax, kHalfMax))) << (16 * (i % 2));
    return words;
}

HostScene HostScene::activate(GaussianCloud cloud) {
    cloud.check_consistent();
    if (cloud.size() > std::numeric_limits<uint32_t>::max() / 64)
        throw InputError("scene", "too many Gaussians for one GPU scene (" + std::to_string(cloud.size()) + ")");
    const size_t n = cloud.size();
    // Activations in float, as torch computes them before calling the reference rasterizer.
    std::vector<float> params(n * 12);
    for (size_t i = 0; i < n; ++i) {
        float* out = &params[i * 12];
        for (int k = 0; k < 3; ++k) out[k] = cloud.positions[3 * i + k];
        out[3] = 1.0f / (1.0f + std::exp(-cloud.opacity_logits[i]));
        for (int k = 0; k < 3; ++k) out[4 + k] = std::exp(cloud.log_scales[3 * i + k]);
        out[7] = 0.0f;
        const float* q = &cloud.rotations[4 * i];
        const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int k = 0; k < 4; ++k) out[8 + k] = q[k] / norm;
    }
    HostScene host;
    host.count = static_cast<uint32_t>(n);
    host.sh_degree = cloud.sh_degree;
    host.params = std::move(params);
    host.sh = std::move(cloud.sh);
    return host;
}

GpuScene GpuScene::upload(const gpu::Context& context, const HostScene& host, const SceneStorage& storage) {
    GpuScene scene;
    scene.count = host.count;
    scene.sh_degree = host.sh_degree;
    scene.params = gpu::upload_buffer(context, host.params, "Gaussian parameters");
    scene.half_sh = storage.half_sh;
    scene.sh = storage.half_sh ? gpu::upload_buffer(context, pack_halves(host.sh), "spherical harmonics (half)")
                               : gpu::upload_buffer(context, host.sh, "spherical harmonics");
    return scene;
}

uint64_t GpuScene::sh_bytes_for(uint32_t count, int sh_degree, bool half_sh) {
    const uint64_t sh_values = uint64_t(count) * sh_coefficients_for_degree(sh_degree) * 3;
    return half_sh ? (sh_values + 1) / 2 * 4 : sh_values * 4;
}

uint64_t GpuScene::bytes_for(uint32_t count, int sh_degree, bool half_sh) {
    return uint64_t(count) * kParamBytesPerGaussian + sh_bytes_for(count, sh_degree, half_sh);
}

}  // namespace vksplat::render
