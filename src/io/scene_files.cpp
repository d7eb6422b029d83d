// Picks a scene reader or writer by format name or by the file's extension.
#include <algorithm>
#include <cctype>
#include <optional>

#include "io/sog_layout.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSupportedExtensions = ".ply, .splat, .spz, .sog, meta.json (SOG), .glb, .pt, .pth";
constexpr const char* kWritableExtensions = ".ply, .compressed.ply, .splat, .spz, .sog, meta.json (SOG), .glb";

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

std::string format_list() {
    std::string list;
    for (const auto& name : scene_formats()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

// The format `path`'s extension names, if any.
std::optional<std::string> format_by_extension(const fs::path& path) {
    const std::string extension = lowercase(path.extension().string());
    if (extension == ".ply")
        return lowercase(path.stem().extension().string()) == ".compressed" ? "compressed-ply" : "ply";
    if (extension == ".splat") return "splat";
    if (extension == ".spz") return "spz";
    if (extension == ".sog" || detail::sog::is_meta_json(path)) return "sog";
    if (extension == ".glb") return "gltf";
    if (extension == ".pt" || extension == ".pth") return "gsplat-pt";
    return std::nullopt;
}

bool is_ply(const std::string& format) { return format == "ply" || format == "compressed-ply"; }

bool is_writable(const std::string& format) { return format != "gsplat-pt"; }

}  // namespace

std::string scene_format_named(const fs::path& path, const std::string& format) {
    if (format.empty()) {
        if (const auto named = format_by_extension(path)) return *named;
        const std::string extension = lowercase(path.extension().string());
        if (extension == ".gltf")
            throw InputError(path.string(), "glTF as JSON with separate buffers (.gltf) is not supported; "
                                            "use binary glTF (.glb)");
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

std::vector<std::string> scene_formats() {
    return {"ply", "compressed-ply", "splat", "spz", "spz-v4", "sog", "gltf", "gsplat-pt"};
}

std::string scene_format_of(const fs::path& path) {
    const std::string format = scene_format_named(path);
    if (is_ply(format) && fs::exists(path)) return is_compressed_ply(path) ? "compressed-ply" : "ply";
    return format;
}

GaussianCloud read_scene(const fs::path& path, std::vector<std::string>* notes, std::string format) {
    // A .ply's header, not its name, tells the flavours apart; an explicit "compressed-ply" is obeyed.
    std::string name = scene_format_named(path, format);
    if (is_ply(name) && (format.empty() || name == "ply") && fs::exists(path))
        name = is_compressed_ply(path) ? "compressed-ply" : "ply";
    if (name == "ply") return read_ply(path, notes);
    if (name == "compressed-ply") return read_compressed_ply(path, notes);
    if (name == "splat") return read_splat(path, notes);
    if (name == "spz" || name == "spz-v4") return read_spz(path, notes);
    if (name == "sog") return read_sog(path, notes);
    if (name == "gltf") return read_gltf(path, notes);
    return read_gsplat_checkpoint(path, notes);
}

std::string check_scene_writable(const fs::path& path, WriteMode mode, const std::string& format) {
    const std::string writable = std::string("; the scene formats vksplat writes are ") + kWritableExtensions +
                                 " (or by name: ply, compressed-ply, splat, spz, spz-v4, sog, gltf)";
    if (format.empty()) {
        const auto named = format_by_extension(path);
        const std::string extension = path.extension().string();
        if (!named)
            throw InputError(path.string(), "cannot write a scene as " +
                                                (extension.empty() ? std::string("a file without an extension")
                                                                   : "'" + extension + "'") +
                                                writable);
    }
    const std::string name = scene_format_named(path, format);
    if (!is_writable(name))
        throw InputError(path.string(), "cannot write format '" + name + "': it is read-only here" + writable);
    // A SOG folder's textures are outputs too.
    for (const fs::path& file : name == "sog" ? detail::sog::output_files(path) : std::vector<fs::path>{path})
        check_writable(file, mode);
    return name;
}

void write_scene(const GaussianCloud& cloud, const fs::path& path, WriteMode mode, std::string format) {
    const std::string name = check_scene_writable(path, mode, format);
    if (name == "ply") return write_ply(cloud, path, mode);
    if (name == "compressed-ply") return write_compressed_ply(cloud, path, mode);
    if (name == "splat") return write_splat(cloud, path, mode);
    if (name == "sog") return write_sog(cloud, path, mode);
    if (name == "gltf") return write_gltf(cloud, path, mode);
    return write_spz(cloud, path, mode, name == "spz-v4" ? 4 : 3);
}

}  // namespace vksplat::io
