// COLMAP models to cameras. COLMAP poses are already world-to-camera with OpenCV axes, and its
// principal point uses our pixel convention (the top-left pixel's centre is at (0.5, 0.5)), so
// everything maps directly; only lens distortion has no place in a pinhole Camera.
#include <algorithm>
#include <cmath>
#include <cstdint>

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

// Sets the camera's intrinsics from a COLMAP camera; returns the distortion parameters it drops.
std::vector<double> apply_intrinsics(const detail::ColmapIntrinsics& intrinsics, const std::string& at,
                                     Camera& camera) {
    struct Model {
        const char* name;
        size_t params;
        bool one_focal;  // f cx cy ... rather than fx fy cx cy ...
    };
    static constexpr Model models[] = {{"SIMPLE_PINHOLE", 3, true},
                                       {"PINHOLE", 4, false},
                                       {"SIMPLE_RADIAL", 4, true},
                                       {"RADIAL", 5, true},
                                       {"OPENCV", 8, false}};
    const auto model =
        std::find_if(std::begin(models), std::end(models), [&](const Model& m) { return intrinsics.model == m.name; });
    if (model == std::end(models))
        throw InputError(at, "camera model " + intrinsics.model +
                                 " is not supported (PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV are)");
    const auto& p = intrinsics.params;
    if (p.size() != model->params)
        throw InputError(at, intrinsics.model + " needs " + std::to_string(model->params) + " parameters, got " +
                                 std::to_string(p.size()));
    const size_t first_principal = model->one_focal ? 1 : 2;
    if (intrinsics.width > INT32_MAX || intrinsics.height > INT32_MAX)
        throw InputError(at, "image size " + std::to_string(intrinsics.width) + "x" +
                                 std::to_string(intrinsics.height) + " is absurd");
    camera.width = static_cast<int>(intrinsics.width);
    camera.height = static_cast<int>(intrinsics.height);
    camera.fx = p[0];
    camera.fy = model->one_focal ? p[0] : p[1];
    camera.cx = p[first_principal];
    camera.cy = p[first_principal + 1];
    return {p.begin() + static_cast<long>(first_principal + 2), p.end()};
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

std::vector<Camera> read_colmap_cameras(const fs::path& dir, std::vector<std::string>* warnings) {
    const ModelFiles files = locate_model(dir);
    const auto intrinsics = files.binary ? detail::read_colmap_cameras_binary(files.cameras)
                                         : detail::read_colmap_cameras_text(files.cameras);
    auto images =
        files.binary ? detail::read_colmap_images_binary(files.images) : detail::read_colmap_images_text(files.images);
    std::sort(images.begin(), images.end(), [](const auto& a, const auto& b) { return a.name < b.name; });

    std::vector<uint32_t> warned;
    std::vector<Camera> cameras;
    for (size_t index = 0; index < images.size(); ++index) {
        const auto& image = images[index];
        const std::string at = files.images.string() + ": camera " + std::to_string(index) + " ('" + image.name + "')";
        const auto found = intrinsics.find(image.camera_id);
        if (found == intrinsics.end())
            throw InputError(at, "refers to COLMAP camera " + std::to_string(image.camera_id) + ", which " +
                                     files.cameras.string() + " does not define");
        Camera camera;
        camera.name = image.name;
        const auto distortion = apply_intrinsics(
            found->second, files.cameras.string() + ": camera " + std::to_string(image.camera_id), camera);
        if (!distortion.empty() && warnings &&
            std::find(warned.begin(), warned.end(), image.camera_id) == warned.end()) {
            std::string values;
            for (double d : distortion) values += (values.empty() ? "" : ", ") + std::to_string(d);
            warnings->push_back(files.cameras.string() + ": camera " + std::to_string(image.camera_id) + " (" +
                                found->second.model + "): distortion (" + values +
                                ") is ignored; images are treated as undistorted pinhole images");
            warned.push_back(image.camera_id);
        }
        camera.rotation = rotation_of(image.qvec, at);
        camera.translation = {image.tvec[0], image.tvec[1], image.tvec[2]};
        detail::check_camera(camera, at);
        cameras.push_back(std::move(camera));
    }
    return cameras;
}

}  // namespace vksplat::io
