#pragma once
// Renderer: renders a GaussianCloud with Vulkan compute, matching the reference rasterizer.
//
//   gpu::Context context;                 // or adopt an application's device (see Context)
//   Renderer renderer(context);
//   auto report = renderer.set_scene(cloud);   // sanitises a copy and uploads it
//   RenderOutput image = renderer.render(camera, settings);
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/gpu/context.hpp"
#include "vksplat/render/render_target.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

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
    uint64_t scene_bytes = 0;        // of which the scene's parameters and SH
    uint32_t tile_key_bits = 0;      // bits the tile sort sorted by
    uint32_t chunks = 1;             // depth-ordered chunks the frame was split into (memory budget)
};

// How the scene is kept in device memory.
struct SceneStorage {
    // SH coefficients as IEEE halves (round to nearest): 96 instead of 192 bytes per Gaussian at
    // degree 3, the largest part of a scene. A half keeps 11 significant bits, so a colour moves
    // by about 1e-4 of its value (well under an 8-bit step); off by default so that renders stay
    // within float rounding of the reference rasterizer.
    bool half_sh = false;
    // Device memory the renderer may hold, in bytes; 0: the context's budget (ContextOptions::
    // memory_budget, else the device's own limit). A frame that does not fit is rendered in K
    // chunks: the scene stays in host memory, is split by view depth (as the depth sort orders
    // it) and each chunk is uploaded and blended front to back, every pixel carrying its colour,
    // transmittance, depth sum, contributor count and whether it stopped to the next chunk, so
    // the picture is the unchunked one. Bound: FrameStats::device_bytes, every device buffer the
    // renderer holds (scene or chunk, frame buffers, sort and scan scratch, carried state), stays
    // within the budget, also while buffers grow; not counted are the driver's rounding of each
    // allocation, pipelines and command buffers, and the host-visible staging and readback
    // buffers. The host then holds the activated scene (48 bytes + SH per Gaussian) and a staging
    // copy of one chunk. Once a frame has needed chunks the scene stays on the host. Chunked
    // frames gather per-Gaussian statistics too (the same numbers, but for float rounding of the
    // blend weight's subgroup sums on some devices), cannot be record()ed (it
    // throws GpuError), and cost an upload of the scene per frame. With the default budget and a scene that fits, no
    // host copy is kept: a frame beyond the device's limit then fails with an out-of-memory
    // GpuError that suggests a budget.
    uint64_t memory_budget = 0;
};

class Renderer {
public:
    explicit Renderer(const gpu::Context& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Sanitises a copy of the cloud (see sanitize()) and uploads it; returns what was fixed.
    SanitizeReport set_scene(const GaussianCloud& cloud, const SceneStorage& storage = {});
    size_t scene_size() const;

    // Renders one view. Throws InputError for an invalid camera, GpuError for device failures.
    RenderOutput render(const Camera& camera, const RenderSettings& settings = {});
    // Renders without reading the image back (for timing); the stats are filled in as usual.
    void render_gpu_only(const Camera& camera, const RenderSettings& settings = {});
    // Renders one view for its per-Gaussian statistics alone (settings.gather_stats is implied):
    // the frame of render() with gather_stats, blend pass included (it measures them), returning
    // the same numbers as its .stats, but only they come back from the device, not the picture
    // (24 bytes a pixel, whose copy and unpacking take a GPU longer than the frame itself). For
    // passes that score views.
    GaussianStats render_stats(const Camera& camera, const RenderSettings& settings = {});
    // The statistics of render_stats for each of `cameras`, summed per Gaussian. With the scene
    // whole on the device and no memory budget set (SceneStorage::memory_budget, the context's),
    // one more pass adds each view's into totals on the device, read back once at the end: a
    // view's statistics readback costs more than its frame (bonsai's settling scored 4 ms a view
    // that way on an H200). Otherwise every view's come back and are summed here. The blend
    // weights are summed exactly in fixed point on the device, in double here. `progress(done,
    // total)` after each view.
    GaussianTotals render_stats_totals(const std::vector<Camera>& cameras, const RenderSettings& settings = {},
                                       const std::function<void(size_t, size_t)>& progress = {});
    // Records the render of one view into `command_buffer`, which the application has begun and
    // will submit, leaving the picture in the application's image or buffer. Submits nothing and
    // waits for nothing, except the context's queue when buffers must grow. The synchronisation
    // contract (barriers, layouts, what the application must do) is in render/render_target.hpp.
    // After it, last_frame() tells the counters of the last recorded frame that finished, with no
    // stage times. Throws std::invalid_argument for a bad target or gather_stats (render() only).
    void record(VkCommandBuffer command_buffer, const Camera& camera, const RenderSettings& settings,
                const RenderTarget& target);

    const FrameStats& last_frame() const;
    // The device it renders on, for passes that work on its output there (cluster projection).
    const gpu::Context& context() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat
