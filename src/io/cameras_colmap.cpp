// COLMAP models to cameras. COLMAP poses are already world-to-camera with OpenCV axes, and its
// principal point uses our pixel convention (the top-left pixel's centre is at (0.5, 0.5)), so
// everything maps directly; only lens distortion has no place in a pinhole Camera: read_colmap_cameras
// leaves it out with a warning, and a data set (dataset.cpp) undistorts its photos (undistort.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "io/colmap_model.hpp"
#include "io/json_fields.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

struct ModelFiles {
    fs::path cameras;
    fs::path images;
    bool binary = false;
};

// The model in dir, dir/sparse/0 or dir/0; binary files win over text, as in COLMAP.
ModelFiles locate_model(const fs::path& dir) {
    if (!fs::is_directory(dir))
        throw InputError(dir.string(),
                         fs::exists(dir) ? "is not a folder (expected a COLMAP model folder)" : "no such folder");
    for (const fs::path& folder : {dir, dir / "sparse" / "0", dir / "0"}) {
        if (fs::exists(folder / "cameras.bin") && fs::exists(folder / "images.bin"))
            return {folder / "cameras.bin", folder / "images.bin", true};
        if (fs::exists(folder / "cameras.txt") && fs::exists(folder / "images.txt"))
            return {folder / "cameras.txt", folder / "images.txt", false};
    }
    throw InputError(dir.string(), "no COLMAP model (cameras.bin + images.bin or cameras.txt + images.txt) in " +
                                       dir.string() + ", " + (dir / "sparse" / "0").string() + " or " +
                                       (dir / "0").string());
}

// A COLMAP camera's pinhole and distortion, its parameters checked against its model.
detail::ColmapLens lens_of(const detail::ColmapIntrinsics& intrinsics, const std::string& at) {
    struct Model {
        const char* name;
        bool one_focal;  // f cx cy ... rather than fx fy cx cy ...
        std::vector<std::string> distortion;
    };
    static const Model models[] = {{"SIMPLE_PINHOLE", true, {}},
                                   {"PINHOLE", false, {}},
                                   {"SIMPLE_RADIAL", true, {"k"}},
                                   {"RADIAL", true, {"k1", "k2"}},
                                   {"OPENCV", false, {"k1", "k2", "p1", "p2"}},
                                   {"FULL_OPENCV", false, {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"}}};
    const auto model =
        std::find_if(std::begin(models), std::end(models), [&](const Model& m) { return intrinsics.model == m.name; });
    if (model == std::end(models))
        throw InputError(at, "camera model " + intrinsics.model +
                                 " is not supported (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV and "
                                 "FULL_OPENCV are; COLMAP's image_undistorter turns other models into PINHOLE)");
    const auto& p = intrinsics.params;
    const size_t first_principal = model->one_focal ? 1 : 2;
    const size_t count = first_principal + 2 + model->distortion.size();
    if (p.size() != count)
        throw InputError(at, intrinsics.model + " needs " + std::to_string(count) + " parameters, got " +
                                 std::to_string(p.size()));
    if (intrinsics.width > INT32_MAX || intrinsics.height > INT32_MAX)
        throw InputError(at, "image size " + std::to_string(intrinsics.width) + "x" +
                                 std::to_string(intrinsics.height) + " is absurd");
    detail::ColmapLens lens;
    lens.model = intrinsics.model;
    lens.width = static_cast<int>(intrinsics.width);
    lens.height = static_cast<int>(intrinsics.height);
    lens.fx = p[0];
    lens.fy = model->one_focal ? p[0] : p[1];
    lens.cx = p[first_principal];
    lens.cy = p[first_principal + 1];
    lens.distortion_names = model->distortion;
    lens.distortion.assign(p.begin() + static_cast<long>(first_principal + 2), p.end());
    return lens;
}

// Rotation matrix of the quaternion (w, x, y, z), normalised first as COLMAP does.
glm::dmat3 rotation_of(const double* q, const std::string& at) {
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(norm > 0) || !std::isfinite(norm)) throw InputError(at, "quaternion has zero or non-finite length");
    const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
    glm::dmat3 r;  // r[column][row]
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    r[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    r[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    return r;
}

}  // namespace

bool detail::ColmapLens::distorted() const {
    return std::any_of(distortion.begin(), distortion.end(), [](double d) { return d != 0; });
}

std::string detail::ColmapLens::description() const {
    std::ostringstream text;
    text << model;
    for (size_t i = 0; i < distortion.size(); ++i) text << ' ' << distortion_names[i] << '=' << distortion[i];
    return text.str();
}

detail::ColmapCameras detail::read_colmap_lens_cameras(const fs::path& dir) {
    const ModelFiles files = locate_model(dir);
    const auto intrinsics = files.binary ? detail::read_colmap_cameras_binary(files.cameras)
                                         : detail::read_colmap_cameras_text(files.cameras);
    auto images =
        files.binary ? detail::read_colmap_images_binary(files.images) : detail::read_colmap_images_text(files.images);
    std::sort(images.begin(), images.end(), [](const auto& a, const auto& b) { return a.name < b.name; });

    ColmapCameras model;
    model.cameras_file = files.cameras;
    for (size_t index = 0; index < images.size(); ++index) {
        const auto& image = images[index];
        const std::string at = files.images.string() + ": camera " + std::to_string(index) + " ('" + image.name + "')";
        const auto found = intrinsics.find(image.camera_id);
        if (found == intrinsics.end())
            throw InputError(at, "refers to COLMAP camera " + std::to_string(image.camera_id) + ", which " +
                                     files.cameras.string() + " does not define");
        auto lens = model.lenses.find(image.camera_id);
        if (lens == model.lenses.end())
            lens = model.lenses
                       .emplace(image.camera_id,
                                lens_of(found->second,
                                        files.cameras.string() + ": camera " + std::to_string(image.camera_id)))
                       .first;
        Camera camera;
        camera.name = image.name;
        camera.width = lens->second.width;
        camera.height = lens->second.height;
        camera.fx = lens->second.fx;
        camera.fy = lens->second.fy;
        camera.cx = lens->second.cx;
        camera.cy = lens->second.cy;
        camera.rotation = rotation_of(image.qvec, at);
        camera.translation = {image.tvec[0], image.tvec[1], image.tvec[2]};
        detail::check_camera(camera, at);
        model.cameras.push_back(std::move(camera));
        model.camera_ids.push_back(image.camera_id);
    }
    return model;
}

std::vector<Camera> read_colmap_cameras(const fs::path& dir, std::vector<std::string>* warnings) {
    detail::ColmapCameras model = detail::read_colmap_lens_cameras(dir);
    for (const auto& [id, lens] : model.lenses) {
        if (!warnings || !lens.distorted()) continue;
        warnings->push_back(model.cameras_file.string() + ": camera " + std::to_string(id) + " (" +
                            lens.description() +
                            "): distortion is ignored; images are treated as undistorted pinhole images (training "
                            "from the data folder undistorts them)");
    }
    return std::move(model.cameras);
}

}  // namespace vksplat::io
