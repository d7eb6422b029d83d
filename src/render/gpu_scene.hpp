#pragma once
// GpuScene: a sanitised GaussianCloud on the device, activated the way the reference's Python
// side hands it to the rasterizer (exp scales, sigmoid opacity, normalised quaternions).
// HostScene is the same data in host memory: what the whole-scene upload copies, and what a
// frame too large for the memory budget uploads from, one depth-ordered chunk at a time.
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/buffer.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::render {

struct HostScene {
    uint32_t count = 0;
    int sh_degree = 0;
    std::vector<float> params;  // 12 floats per Gaussian, laid out as GpuScene::params
    std::vector<float> sh;      // sh_floats() per Gaussian, [coefficient][rgb]

    // Takes the cloud by value so that a caller's temporary gives up its SH without a copy.
    static HostScene activate(GaussianCloud cloud);
    uint32_t sh_floats() const { return static_cast<uint32_t>(sh_coefficients_for_degree(sh_degree)) * 3; }
};

struct GpuScene {
    uint32_t count = 0;
    int sh_degree = 0;
    bool half_sh = false;  // sh holds halves packed two per uint (SceneStorage::half_sh)
    gpu::Buffer params;  // 3 vec4 per Gaussian: (position, opacity), (scale, 0), (quaternion w, x, y, z)
    gpu::Buffer sh;      // [Gaussian][coefficient][rgb], float or half

    static constexpr uint64_t kParamBytesPerGaussian = 48;  // the 3 vec4 of params

    static GpuScene upload(const gpu::Context& context, const HostScene& host, const SceneStorage& storage);
    // Device bytes of `count` Gaussians' SH, float or packed halves.
    static uint64_t sh_bytes_for(uint32_t count, int sh_degree, bool half_sh);
    // Device bytes of `count` Gaussians' parameters and SH (what upload() allocates).
    static uint64_t bytes_for(uint32_t count, int sh_degree, bool half_sh);
};

// Halves packed two per uint, low half first (what unpackHalf2x16 reads); an odd count is padded.
std::vector<uint32_t> pack_halves(std::span<const float> values);

}  // namespace vksplat::render
