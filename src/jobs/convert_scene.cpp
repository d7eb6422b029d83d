#include "vksplat/jobs/convert_scene.hpp"

#include <algorithm>
#include <cctype>

#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

// The format a file will be read or written as; io::scene_format_of throws, naming the file and
// the supported extensions, for an extension it does not know.
std::string resolve_format(const fs::path& path, const std::string& named) {
    if (named.empty()) return io::scene_format_of(path);
    const std::string name = lowercase(named);
    const auto names = io::scene_formats();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw InputError(path.string(), "unknown scene format '" + named + "'; supported: " + list);
    }
    return name;
}

// The SH degree a format keeps, so the user is told what was dropped rather than surprised.
int kept_sh_degree(const std::string& format, int sh_degree) { return format == "splat" ? 0 : sh_degree; }

}  // namespace

ConvertResult convert_scene(const fs::path& input, const fs::path& output, const ConvertOptions& options) {
    ConvertResult result;
    if (!fs::exists(input)) throw InputError(input.string(), "no such file");
    result.input_format = resolve_format(input, options.input_format);
    result.output_format = resolve_format(output, options.output_format);
    if (options.mode == io::WriteMode::refuse_existing && fs::exists(output))
        throw InputError(output.string(), "already exists; not overwritten (use --force to replace it)");
    if (fs::exists(output) && fs::equivalent(input, output))
        throw InputError(output.string(), "is the input file; write the conversion to another file");

    const GaussianCloud cloud = io::read_scene(input, &result.notes, result.input_format);
    result.gaussians = cloud.size();
    result.input_sh_degree = cloud.sh_degree;
    result.output_sh_degree = kept_sh_degree(result.output_format, cloud.sh_degree);
    io::write_scene(cloud, output, options.mode, result.output_format);
    if (result.output_sh_degree < result.input_sh_degree)
        result.notes.push_back("SH degree " + std::to_string(result.input_sh_degree) + " reduced to " +
                               std::to_string(result.output_sh_degree) + ": " + result.output_format +
                               " holds only the base colour");
    if (result.output_format == "spz")
        result.notes.push_back("spz stores every value in fixed point: positions, colours, scales, rotations "
                               "and SH are rounded");
    return result;
}

}  // namespace vksplat::jobs
