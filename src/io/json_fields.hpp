#pragma once
// Typed access to JSON camera files, with errors that say which key of which camera is wrong.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::io::detail {

// The parsed file; throws InputError if it is missing or not valid JSON.
nlohmann::json read_json_file(const std::filesystem::path& path);
// The parsed text (a file's bytes from elsewhere, such as a zip); throws InputError naming `where`
// if it is not valid JSON.
nlohmann::json parse_json(std::string_view text, const std::string& where);

// Each throws InputError(at, ...) if the key is missing or holds the wrong type.
const nlohmann::json& field(const nlohmann::json& object, const char* key, const std::string& at);
double number_field(const nlohmann::json& object, const char* key, const std::string& at);
int int_field(const nlohmann::json& object, const char* key, const std::string& at);
std::string string_field(const nlohmann::json& object, const char* key, const std::string& at);
// A rows x cols matrix given as a list of rows (rows == 1: a flat list), row-major.
std::vector<double> matrix_field(const nlohmann::json& object, const char* key, size_t rows, size_t cols,
                                 const std::string& at);

// Camera::validate(), its complaint rethrown as InputError(at, ...).
void check_camera(const Camera& camera, const std::string& at);

}  // namespace vksplat::io::detail
