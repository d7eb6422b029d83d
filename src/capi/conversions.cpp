#include "capi/conversions.hpp"

namespace vksplat::capi {

// The C struct's rotation is row-major; glm's rotation[c][r] is row r, column c.
Camera to_camera(const vksplat_camera& camera, const std::string& name) {
    Camera out;
    out.name = name;
    out.width = camera.width;
    out.height = camera.height;
    out.fx = camera.fx;
    out.fy = camera.fy;
    out.cx = camera.cx;
    out.cy = camera.cy;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) out.rotation[c][r] = camera.rotation[r * 3 + c];
        out.translation[r] = camera.translation[r];
    }
    return out;
}

vksplat_camera from_camera(const Camera& camera) {
    vksplat_camera out{};
    out.width = camera.width;
    out.height = camera.height;
    out.fx = camera.fx;
    out.fy = camera.fy;
    out.cx = camera.cx;
    out.cy = camera.cy;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) out.rotation[r * 3 + c] = camera.rotation[c][r];
        out.translation[r] = camera.translation[r];
    }
    return out;
}

RenderSettings to_settings(const vksplat_render_settings* settings) {
    RenderSettings out;
    if (!settings) return out;
    for (int c = 0; c < 3; ++c) out.background[static_cast<size_t>(c)] = settings->background[c];
    out.max_sh_degree = settings->max_sh_degree;
    return out;
}

}  // namespace vksplat::capi
