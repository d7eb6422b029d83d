// read_cameras(): tells the camera file formats apart by what the path holds.
#include "io/camera_json_readers.hpp"
#include "io/json_fields.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io {

std::vector<Camera> read_cameras(const std::filesystem::path& path, std::vector<std::string>* warnings) {
    if (std::filesystem::is_directory(path)) return read_colmap_cameras(path, warnings);
    const nlohmann::json document = detail::read_json_file(path);
    if (document.is_array()) return detail::inria_cameras_from_json(document, path);
    if (document.is_object() && document.contains("frames")) return detail::nerf_cameras_from_json(document, path);
    throw InputError(path.string(),
                     "is neither an INRIA cameras.json (a list of cameras) nor a NeRF transforms file "
                     "(an object with 'frames')");
}

}  // namespace vksplat::io
