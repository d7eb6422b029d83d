// Typed JSON access for the camera readers: nlohmann's own exceptions name neither the file nor the
// camera, so every access goes through these checks.
#include "io/json_fields.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <exception>
#include <utility>

#include "vksplat/error.hpp"

namespace vksplat::io::detail {

using nlohmann::json;

namespace {

// nlohmann's own exceptions do not name the file.
template <typename Input>
json parse_or_refuse(Input&& input, const std::string& where) {
    try {
        return json::parse(std::forward<Input>(input));
    } catch (const json::parse_error& error) {
        throw InputError(where, std::string("malformed JSON: ") + error.what());
    } catch (const json::exception& error) {
        // A number beyond a double's range (1e400) is nlohmann's out_of_range, not a parse_error.
        throw InputError(where, std::string("unreadable JSON: ") + error.what());
    }
}

}  // namespace

json read_json_file(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path.string(), std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    return parse_or_refuse(in, path.string());
}

json parse_json(std::string_view text, const std::string& where) { return parse_or_refuse(text, where); }

const json& field(const json& object, const char* key, const std::string& at) {
    if (!object.is_object())
        throw InputError(at, std::string("is a JSON ") + object.type_name() + ", expected an object");
    const auto found = object.find(key);
    if (found == object.end()) throw InputError(at, std::string("missing key '") + key + "'");
    return *found;
}

namespace {

InputError wrong_type(const char* key, const json& value, const char* expected, const std::string& at) {
    return InputError(at, std::string("key '") + key + "' is a " + value.type_name() + ", expected " + expected);
}

}  // namespace

double number_field(const json& object, const char* key, const std::string& at) {
    const json& value = field(object, key, at);
    if (!value.is_number()) throw wrong_type(key, value, "a number", at);
    return value.get<double>();
}

int int_field(const json& object, const char* key, const std::string& at) {
    const json& value = field(object, key, at);
    // Some writers store sizes as 800.0: accept a float with an integral value.
    const double number = value.is_number() ? value.get<double>() : std::nan("");
    if (!value.is_number() || number != std::floor(number) || std::abs(number) > std::numeric_limits<int>::max())
        throw wrong_type(key, value, "an integer", at);
    return static_cast<int>(number);
}

std::string string_field(const json& object, const char* key, const std::string& at) {
    const json& value = field(object, key, at);
    if (!value.is_string()) throw wrong_type(key, value, "a string", at);
    return value.get<std::string>();
}

std::vector<double> matrix_field(const json& object, const char* key, size_t rows, size_t cols, const std::string& at) {
    const json& value = field(object, key, at);
    const std::string shape =
        rows == 1 ? "a list of " + std::to_string(cols) + " numbers"
                  : "a list of " + std::to_string(rows) + " rows of " + std::to_string(cols) + " numbers";
    std::vector<double> values;
    const auto append_row = [&](const json& row) {
        if (!row.is_array() || row.size() != cols) return false;
        for (const json& number : row) {
            if (!number.is_number()) return false;
            values.push_back(number.get<double>());
        }
        return true;
    };
    bool good = rows == 1 ? append_row(value) : value.is_array() && value.size() == rows;
    for (size_t r = 0; good && rows > 1 && r < rows; ++r) good = append_row(value[r]);
    if (!good) throw InputError(at, std::string("key '") + key + "' is not " + shape);
    return values;
}

void check_camera(const Camera& camera, const std::string& at) {
    if (const std::string problem = camera.problem(); !problem.empty()) throw InputError(at, problem);
}

}  // namespace vksplat::io::detail
