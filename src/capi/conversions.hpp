#pragma once
// The C API's plain structs to and from the C++ library's types.
#include <string>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render_types.hpp"
#include "vksplat/vksplat.h"

namespace vksplat::capi {

// `name` is what the library's messages call the camera ("camera 'views[2]': ...").
Camera to_camera(const vksplat_camera& camera, const std::string& name);
vksplat_camera from_camera(const Camera& camera);
// NULL: the defaults (vksplat_render_settings_default()).
RenderSettings to_settings(const vksplat_render_settings* settings);

}  // namespace vksplat::capi
