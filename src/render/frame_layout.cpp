#include "render/frame_layout.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "vksplat/constants.hpp"
#include "vksplat/error.hpp"

namespace vksplat::render {
namespace {

uint32_t tiles_across(uint32_t width) { return (width + constants::kTileWidth - 1) / constants::kTileWidth; }
uint32_t tiles_down(uint32_t height) { return (height + constants::kTileHeight - 1) / constants::kTileHeight; }

}  // namespace

ImageExtent image_extent(const Camera& camera) {
    const auto width = static_cast<uint32_t>(camera.width), height = static_cast<uint32_t>(camera.height);
    // A frame indexes its pixels with 32 bits: past that the count would wrap (65536^2 to 0) and a
    // frame be sized for none of them.
    if (uint64_t(width) * height > std::numeric_limits<uint32_t>::max())
        throw InputError("camera '" + camera.name + "'", "its " + std::to_string(width) + "x" + std::to_string(height) +
                                                             " image has more pixels than a frame can index (2^32)");
    return {width * height, tiles_across(width) * tiles_down(height)};
}

CameraParams make_camera_params(const Camera& camera, const RenderSettings& settings, uint32_t gaussian_count,
                                int scene_sh_degree, bool scene_half_sh, uint32_t entry_capacity) {
    // Every frame's parameters, the renderer's and training's alike, are made here: the one place
    // that sees every background.
    settings.validate();
    CameraParams p{};
    float* rows[3] = {p.view_row0.v, p.view_row1.v, p.view_row2.v};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) rows[r][c] = static_cast<float>(camera.rotation[c][r]);
        rows[r][3] = static_cast<float>(camera.translation[r]);
    }
    const glm::dvec3 centre = camera.centre();
    for (int i = 0; i < 3; ++i) p.position[i] = static_cast<float>(centre[i]);

    // Pixel centres sit at integer coordinates in the reference (ndc2Pix), hence the -0.5.
    p.focal_principal[0] = static_cast<float>(camera.fx);
    p.focal_principal[1] = static_cast<float>(camera.fy);
    p.focal_principal[2] = static_cast<float>(camera.cx - 0.5);
    p.focal_principal[3] = static_cast<float>(camera.cy - 0.5);

    // The reference clamps x/z to +-1.3 tan(fov_x / 2): the image edge plus 30% of the half
    // width beyond it. With an off-centre principal point the edges sit at different angles on
    // either side, so each side gets its own edge plus the same margin; centred, this is exactly
    // the reference's limit.
    const double margin_x = (constants::kJacobianClamp - 1.0) * camera.tan_half_fov_x();
    const double margin_y = (constants::kJacobianClamp - 1.0) * camera.tan_half_fov_y();
    p.jacobian_limits[0] = static_cast<float>(camera.cx / camera.fx + margin_x);
    p.jacobian_limits[1] = static_cast<float>((camera.width - camera.cx) / camera.fx + margin_x);
    p.jacobian_limits[2] = static_cast<float>(camera.cy / camera.fy + margin_y);
    p.jacobian_limits[3] = static_cast<float>((camera.height - camera.cy) / camera.fy + margin_y);

    p.size[0] = static_cast<uint32_t>(camera.width);
    p.size[1] = static_cast<uint32_t>(camera.height);
    p.size[2] = tiles_across(p.size[0]);
    p.size[3] = tiles_down(p.size[1]);
    for (int i = 0; i < 3; ++i) p.background[i] = settings.background[i];

    p.gaussian_count = gaussian_count;
    p.sh_degree = static_cast<uint32_t>(std::clamp(std::min(settings.max_sh_degree, scene_sh_degree), 0, 3));
    p.sh_stride = static_cast<uint32_t>(sh_coefficients_for_degree(scene_sh_degree));
    p.sh_half = scene_half_sh ? 1u : 0u;
    // A plain frame's passes read the splats' footprints and colours; the projected means, depths
    // and radii are for the statistics (and training, DifferentiableRenderer::record_forward).
    p.write_projection = settings.gather_stats ? 1u : 0u;
    p.entry_capacity = entry_capacity;
    return p;
}

}  // namespace vksplat::render
