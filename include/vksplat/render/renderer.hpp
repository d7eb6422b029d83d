#pragma once
// Renderer: renders a GaussianCloud with Vulkan compute, matching the reference rasterizer.
//
//   gpu::Context context;                 // or adopt an application's device (see Context)
//   Renderer renderer(context);
//   auto report = renderer.set_scene(cloud);   // sanitises a copy and uploads it
//   RenderOutput image = renderer.render(camera, settings);
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vksplat/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene.hpp"

namespace vksplat {

struct StageTiming {
    std::string stage;
    double milliseconds = 0;
};

// What the last frame did, from the GPU's own counters and timestamp queries.
struct FrameStats {
    uint32_t gaussians = 0;
    uint32_t visible = 0;            // splats that survived culling
    uint32_t tile_entries = 0;       // (tile, splat) pairs sorted
    uint32_t attempts = 1;           // > 1 when the entry buffers had to grow and the frame re-ran
    std::vector<StageTiming> stages; // GPU time per stage, in recording order
    double gpu_milliseconds = 0;     // first to last dispatch of the frame
    uint64_t device_bytes = 0;       // device memory the renderer holds
};

class Renderer {
public:
    explicit Renderer(const gpu::Context& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Sanitises a copy of the cloud (see sanitize()) and uploads it; returns what was fixed.
    SanitizeReport set_scene(const GaussianCloud& cloud);
    size_t scene_size() const;

    // Renders one view. Throws InputError for an invalid camera, GpuError for device failures.
    RenderOutput render(const Camera& camera, const RenderSettings& settings = {});
    // Renders without reading the image back (for timing); the stats are filled in as usual.
    void render_gpu_only(const Camera& camera, const RenderSettings& settings = {});

    const FrameStats& last_frame() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat
