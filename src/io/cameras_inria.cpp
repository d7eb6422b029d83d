// INRIA cameras.json: camera-to-world rotation (as rows) and camera centre, OpenCV axes.
#include "io/camera_json_readers.hpp"
#include "io/json_fields.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io {
namespace detail {

std::vector<Camera> inria_cameras_from_json(const nlohmann::json& document, const std::filesystem::path& path) {
    const std::string where = path.string();
    if (!document.is_array())
        throw InputError(where, std::string("is a JSON ") + document.type_name() + ", expected a list of cameras");
    std::vector<Camera> cameras;
    for (size_t index = 0; index < document.size(); ++index) {
        const nlohmann::json& entry = document[index];
        std::string at = where + ": camera " + std::to_string(index);
        Camera camera;
        camera.name = string_field(entry, "img_name", at);
        at += " ('" + camera.name + "')";
        camera.width = int_field(entry, "width", at);
        camera.height = int_field(entry, "height", at);
        camera.fx = number_field(entry, "fx", at);
        camera.fy = number_field(entry, "fy", at);
        camera.cx = entry.contains("cx") ? number_field(entry, "cx", at) : camera.width / 2.0;
        camera.cy = entry.contains("cy") ? number_field(entry, "cy", at) : camera.height / 2.0;
        if (const auto split = entry.find("split"); split != entry.end() && split->is_string())
            camera.split = split->get<std::string>();
        const auto c2w = matrix_field(entry, "rotation", 3, 3, at);  // row-major
        const auto position = matrix_field(entry, "position", 1, 3, at);
        // World-to-camera is the transpose: its column c (glm's [c]) is row c of the file's matrix.
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) camera.rotation[c][r] = c2w[static_cast<size_t>(c * 3 + r)];
        camera.translation = -(camera.rotation * glm::dvec3(position[0], position[1], position[2]));
        check_camera(camera, at);
        cameras.push_back(std::move(camera));
    }
    return cameras;
}

}  // namespace detail

std::vector<Camera> read_inria_cameras(const std::filesystem::path& path) {
    return detail::inria_cameras_from_json(detail::read_json_file(path), path);
}

}  // namespace vksplat::io
