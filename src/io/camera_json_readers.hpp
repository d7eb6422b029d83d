#pragma once
// The JSON camera readers on an already parsed document, so that read_cameras() parses a file once
// to learn its format and then hands it on.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::io::detail {

std::vector<Camera> inria_cameras_from_json(const nlohmann::json& document, const std::filesystem::path& path);
std::vector<Camera> nerf_cameras_from_json(const nlohmann::json& document, const std::filesystem::path& path);

}  // namespace vksplat::io::detail
