#pragma once
// GpuScene: a sanitised GaussianCloud on the device, activated the way the reference's Python
// side hands it to the rasterizer (exp scales, sigmoid opacity, normalised quaternions).
#include "gpu/buffer.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/scene.hpp"

namespace vksplat::render {

struct GpuScene {
    uint32_t count = 0;
    int sh_degree = 0;
    bool half_sh = false;  // sh holds halves packed two per uint (SceneStorage::half_sh)
    gpu::Buffer params;  // 3 vec4 per Gaussian: (position, opacity), (scale, 0), (quaternion w, x, y, z)
    gpu::Buffer sh;      // [Gaussian][coefficient][rgb], float or half

    static GpuScene upload(const gpu::Context& context, const GaussianCloud& cloud, const SceneStorage& storage);
};

}  // namespace vksplat::render
