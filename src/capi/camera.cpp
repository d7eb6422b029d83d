// vksplat_camera from a viewpoint (Camera::look_at).
#include "capi/call.hpp"
#include "capi/conversions.hpp"

using vksplat::capi::guarded;
using vksplat::capi::require;

namespace {

glm::dvec3 point(const double* xyz, const char* what) {
    require(xyz, what);
    return {xyz[0], xyz[1], xyz[2]};
}

}  // namespace

extern "C" {

vksplat_status vksplat_camera_look_at(const double eye[3], const double target[3], const double up[3], int width,
                                      int height, double fx, double fy, vksplat_camera* camera,
                                      vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_camera& out = require(camera, "camera");
        out = vksplat::capi::from_camera(vksplat::Camera::look_at(point(eye, "eye"), point(target, "target"),
                                                                  point(up, "up"), width, height, fx, fy));
    });
}

}  // extern "C"
