// Picks a scene reader or writer by format name or by the file's extension.
#include <algorithm>
#include <cctype>

#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSupportedExtensions = ".ply, .splat, .spz, .pt, .pth";

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

std::string format_list() {
    std::string list;
    for (const auto& name : scene_formats()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

}  // namespace

std::string scene_format_named(const fs::path& path, const std::string& format) {
    if (format.empty()) {
        const std::string extension = lowercase(path.extension().string());
        if (extension == ".ply") return "ply";
        if (extension == ".splat") return "splat";
        if (extension == ".spz") return "spz";
        if (extension == ".pt" || extension == ".pth") return "gsplat-pt";
        throw InputError(path.string(), (extension.empty() ? std::string("has no extension")
                                                           : "unknown scene file extension '" + extension + "'") +
                                            "; supported: " + kSupportedExtensions + " (or name the format: " +
                                            format_list() + ")");
    }
    const std::string name = lowercase(format);
    const auto names = scene_formats();
    if (std::find(names.begin(), names.end(), name) == names.end())
        throw InputError(path.string(), "unknown scene format '" + format + "'; supported: " + format_list());
    return name;
}

std::vector<std::string> scene_formats() { return {"ply", "compressed-ply", "splat", "spz", "gsplat-pt"}; }

std::string scene_format_of(const fs::path& path) {
    const std::string format = scene_format_named(path);
    if (format == "ply" && fs::exists(path) && is_compressed_ply(path)) return "compressed-ply";
    return format;
}

GaussianCloud read_scene(const fs::path& path, std::vector<std::string>* notes, std::string format) {
    std::string name = scene_format_named(path, format);
    if (name == "ply" && fs::exists(path) && is_compressed_ply(path)) name = "compressed-ply";
    if (name == "ply") return read_ply(path, notes);
    if (name == "compressed-ply") return read_compressed_ply(path, notes);
    if (name == "splat") return read_splat(path, notes);
    if (name == "spz") return read_spz(path, notes);
    return read_gsplat_checkpoint(path, notes);
}

std::string check_scene_writable(const fs::path& path, WriteMode mode, const std::string& format) {
    const std::string name = scene_format_named(path, format);
    if (name != "ply" && name != "splat" && name != "spz")
        throw InputError(path.string(), "cannot write format '" + name + "': it is read-only here (writable: ply, splat, spz)");
    check_writable(path, mode);
    return name;
}

void write_scene(const GaussianCloud& cloud, const fs::path& path, WriteMode mode, std::string format) {
    const std::string name = check_scene_writable(path, mode, format);
    if (name == "ply") return write_ply(cloud, path, mode);
    if (name == "splat") return write_splat(cloud, path, mode);
    return write_spz(cloud, path, mode);
}

}  // namespace vksplat::io
