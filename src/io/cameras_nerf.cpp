// NeRF transforms_*.json: a horizontal field of view and camera-to-world matrices with OpenGL axes
// (x right, y up, z backwards), turned into OpenCV cameras by flipping the camera's y and z axes.
#include <cmath>

#include "io/camera_json_readers.hpp"
#include "io/json_fields.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::io {
namespace detail {
namespace {

// w and h: the frame's own, else the file's, else the image's size.
void image_size(const nlohmann::json& document, const nlohmann::json& frame, const std::filesystem::path& folder,
                const std::string& file_path, const std::string& at, Camera& camera) {
    for (const nlohmann::json* holder : {&frame, &document}) {
        if (holder->contains("w") && holder->contains("h")) {
            camera.width = int_field(*holder, "w", at);
            camera.height = int_field(*holder, "h", at);
            return;
        }
    }
    std::filesystem::path image = folder / file_path;
    if (!image.has_extension()) image += ".png";  // the Blender scenes leave it out
    if (!std::filesystem::exists(image))
        throw InputError(at, "no w/h keys and no image at " + image.string() + " to take the size from");
    try {
        const auto [width, height] = read_image_size(image);
        camera.width = width;
        camera.height = height;
    } catch (const InputError& e) {
        throw InputError(at, std::string("no w/h keys, and the image's size cannot be read: ") + e.what());
    }
}

}  // namespace

std::vector<Camera> nerf_cameras_from_json(const nlohmann::json& document, const std::filesystem::path& path) {
    const std::string where = path.string();
    const double angle_x = number_field(document, "camera_angle_x", where);
    const nlohmann::json& frames = field(document, "frames", where);
    if (!frames.is_array())
        throw InputError(where, std::string("key 'frames' is a ") + frames.type_name() + ", expected a list");

    std::vector<Camera> cameras;
    for (size_t index = 0; index < frames.size(); ++index) {
        const nlohmann::json& frame = frames[index];
        std::string at = where + ": frame " + std::to_string(index);
        Camera camera;
        camera.name = string_field(frame, "file_path", at);
        at += " ('" + camera.name + "')";
        image_size(document, frame, path.parent_path(), camera.name, at, camera);
        camera.fx = 0.5 * camera.width / std::tan(angle_x / 2);
        camera.fy = document.contains("camera_angle_y")
                        ? 0.5 * camera.height / std::tan(number_field(document, "camera_angle_y", where) / 2)
                        : camera.fx;
        camera.cx = document.contains("cx") ? number_field(document, "cx", where) : camera.width / 2.0;
        camera.cy = document.contains("cy") ? number_field(document, "cy", where) : camera.height / 2.0;

        const auto c2w = matrix_field(frame, "transform_matrix", 4, 4, at);  // row-major, OpenGL camera axes
        // OpenCV camera axes are OpenGL's with y and z negated: negate columns 1 and 2 of the
        // camera-to-world rotation. World-to-camera is its transpose, so glm's column c holds row c.
        const double flip[3] = {1.0, -1.0, -1.0};
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) camera.rotation[c][r] = c2w[static_cast<size_t>(c * 4 + r)] * flip[r];
        const glm::dvec3 centre(c2w[3], c2w[7], c2w[11]);
        camera.translation = -(camera.rotation * centre);
        check_camera(camera, at);
        cameras.push_back(std::move(camera));
    }
    return cameras;
}

}  // namespace detail

std::vector<Camera> read_nerf_transforms(const std::filesystem::path& path) {
    return detail::nerf_cameras_from_json(detail::read_json_file(path), path);
}

}  // namespace vksplat::io
