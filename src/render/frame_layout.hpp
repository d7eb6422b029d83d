#pragma once
// The per-frame camera block and counter slots (declared once, in shaders/render/frame.h) and how a
// camera fills the block.
#include <cstdint>

#include "shaders/render/frame.h"
#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::render {

// The per-frame camera block and the counter slots, as the shaders see them.
using shader::render::CameraParams;
using shader::render::kCounterCount;
using shader::render::kCounterEntries;
using shader::render::kCounterEntriesNeeded;
using shader::render::kCounterEntryArgs;
using shader::render::kCounterGaussians;
using shader::render::kCounterVisible;
using shader::render::kCounterVisibleArgs;

// What an image sizes the per-image frame buffers by: its pixels and its 16x16 tiles (the same
// tiling as CameraParams::size[2..3]).
struct ImageExtent {
    uint32_t pixels = 0, tiles = 0;
};
ImageExtent image_extent(const Camera& camera);

CameraParams make_camera_params(const Camera& camera, const RenderSettings& settings, uint32_t gaussian_count,
                                int scene_sh_degree, bool scene_half_sh, uint32_t entry_capacity);

}  // namespace vksplat::render
