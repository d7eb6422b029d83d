// vksplat_scene: a GaussianCloud read from a file, copied from the caller's arrays, or written out.
#include <string>

#include "capi/call.hpp"
#include "capi/handles.hpp"
#include "vksplat/io/formats.hpp"

using vksplat::capi::guarded;
using vksplat::capi::out_pointer;
using vksplat::capi::require;

namespace {

// The caller's array of `per_gaussian` floats for each of `count` Gaussians, copied into `to`.
void copy_array(std::vector<float>& to, const float* from, size_t count, size_t per_gaussian, const char* what) {
    if (count == 0) return;
    require(from, what);
    to.assign(from, from + count * per_gaussian);
}

}  // namespace

extern "C" {

vksplat_status vksplat_scene_load(const char* path, vksplat_scene** scene, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_scene*& out = out_pointer(scene, "scene");
        require(path, "path");
        out = new vksplat_scene{vksplat::io::read_scene(path)};
    });
}

vksplat_status vksplat_scene_create(const vksplat_scene_data* data, vksplat_scene** scene, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        vksplat_scene*& out = out_pointer(scene, "scene");
        const vksplat_scene_data& in = require(data, "data");
        if (in.sh_degree < 0 || in.sh_degree > 3)
            throw std::invalid_argument("data->sh_degree is " + std::to_string(in.sh_degree) + "; it must be 0 to 3");
        vksplat::GaussianCloud cloud;
        cloud.sh_degree = in.sh_degree;
        copy_array(cloud.positions, in.positions, in.count, 3, "data->positions");
        copy_array(cloud.log_scales, in.log_scales, in.count, 3, "data->log_scales");
        copy_array(cloud.rotations, in.rotations, in.count, 4, "data->rotations");
        copy_array(cloud.opacity_logits, in.opacity_logits, in.count, 1, "data->opacity_logits");
        copy_array(cloud.sh, in.sh, in.count, static_cast<size_t>(cloud.sh_coefficients()) * 3, "data->sh");
        out = new vksplat_scene{std::move(cloud)};
    });
}

vksplat_status vksplat_scene_save(const vksplat_scene* scene, const char* path, int overwrite, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        const vksplat_scene& in = require(scene, "scene");
        require(path, "path");
        vksplat::io::write_scene(in.cloud, path,
                                 overwrite ? vksplat::io::WriteMode::overwrite : vksplat::io::WriteMode::refuse_existing);
    });
}

vksplat_status vksplat_scene_info(const vksplat_scene* scene, size_t* count, int* sh_degree, vksplat_error* error) {
    return guarded(__func__, error, [&] {
        const vksplat_scene& in = require(scene, "scene");
        if (count) *count = in.cloud.size();
        if (sh_degree) *sh_degree = in.cloud.sh_degree;
    });
}

void vksplat_scene_destroy(vksplat_scene* scene) { delete scene; }

}  // extern "C"
