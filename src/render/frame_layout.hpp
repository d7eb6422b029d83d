#pragma once
// C++ twin of shaders/include/frame.glsl: the per-frame camera block and the counter slots.
#include <cstdint>

#include "vksplat/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene.hpp"

namespace vksplat::render {

struct alignas(16) CameraParams {
    float view_row0[4];
    float view_row1[4];
    float view_row2[4];
    float position[4];
    float focal_principal[4];
    float jacobian_limits[4];
    uint32_t size[4];
    float background[4];
    uint32_t gaussian_count;
    uint32_t sh_degree;
    uint32_t sh_stride;
    uint32_t entry_capacity;
    uint32_t sh_half;
    uint32_t write_projection;
    uint32_t padding[2];
};
static_assert(sizeof(CameraParams) == 160, "must match CameraParams in frame.glsl (std430)");

enum Counter : uint32_t {
    kCounterGaussians = 0,
    kCounterVisible = 1,
    kCounterEntriesNeeded = 2,
    kCounterEntries = 3,
    kCounterVisibleArgs = 4,
    kCounterEntryArgs = 7,
    kCounterCount = 10,
};


// What an image sizes the per-image frame buffers by: its pixels and its 16x16 tiles (the same
// tiling as CameraParams::size[2..3]).
struct ImageExtent {
    uint32_t pixels = 0, tiles = 0;
};
ImageExtent image_extent(const Camera& camera);

CameraParams make_camera_params(const Camera& camera, const RenderSettings& settings, uint32_t gaussian_count,
                                int scene_sh_degree, bool scene_half_sh, uint32_t entry_capacity);

}  // namespace vksplat::render
