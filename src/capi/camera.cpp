// vksplat_camera from a viewpoint (Camera::look_at) or from a camera file.
#include <memory>

#include "capi/call.hpp"
#include "capi/conversions.hpp"
#include "vksplat/io/cameras.hpp"

using vksplat::capi::guarded;
using vksplat::capi::out_pointer;
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

vksplat_status vksplat_cameras_load(const char* path, vksplat_camera** cameras, size_t* count, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_camera*& out = out_pointer(cameras, "cameras");
        size_t& out_count = require(count, "count");
        out_count = 0;
        require(path, "path");
        const std::vector<vksplat::Camera> read = vksplat::io::read_cameras(path);
        if (read.empty()) return;
        auto converted = std::make_unique<vksplat_camera[]>(read.size());
        for (size_t i = 0; i < read.size(); ++i) converted[i] = vksplat::capi::from_camera(read[i]);
        out = converted.release();
        out_count = read.size();
    });
}

void vksplat_cameras_free(vksplat_camera* cameras) { delete[] cameras; }

}  // extern "C"
