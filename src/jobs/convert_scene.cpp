#include "vksplat/jobs/convert_scene.hpp"

#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/sh_precision.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

// The SH degree a format keeps, so the user is told what was dropped rather than surprised.
int kept_sh_degree(const std::string& format, int sh_degree) { return format == "splat" ? 0 : sh_degree; }

}  // namespace

ConvertResult convert_scene(const fs::path& input, const fs::path& output, const ConvertOptions& options) {
    ConvertResult result;
    if (!fs::exists(input)) throw InputError(input.string(), "no such file");
    // The input's header may tell a compressed .ply apart; the output's format comes from its name
    // (or options) alone: an existing file there is about to be replaced, whatever it holds.
    result.input_format = options.input_format.empty() ? io::scene_format_of(input)
                                                       : io::scene_format_named(input, options.input_format);
    io::refuse_input_as_output(output, {input});
    result.output_format = io::check_scene_writable(output, options.mode, options.output_format);
    if (options.sh_precision) prune::check_sh_precision(*options.sh_precision);

    GaussianCloud cloud = io::read_scene(input, &result.notes, result.input_format);
    if (options.sh_precision) {
        cloud = prune::with_sh_precision(cloud, *options.sh_precision);
        result.notes.push_back("SH degrees 1 and 2-3 rounded to " + std::to_string(options.sh_precision->degree1_bits) +
                               " and " + std::to_string(options.sh_precision->higher_bits) + " bits of SPZ's byte");
    }
    result.gaussians = cloud.size();
    result.input_sh_degree = cloud.sh_degree;
    result.output_sh_degree = kept_sh_degree(result.output_format, cloud.sh_degree);
    io::write_scene(cloud, output, options.mode, result.output_format);
    if (result.output_sh_degree < result.input_sh_degree)
        result.notes.push_back("SH degree " + std::to_string(result.input_sh_degree) + " reduced to " +
                               std::to_string(result.output_sh_degree) + ": " + result.output_format +
                               " holds only the base colour");
    if (result.output_format == "spz" || result.output_format == "spz-v4")
        result.notes.push_back("spz stores every value in fixed point: positions, colours, scales, rotations "
                               "and SH are rounded");
    if (result.output_format == "sog")
        result.notes.push_back("sog rounds positions (16 bits) and rotations (8 bits), takes scales and colours from "
                               "codebooks of 256 and the higher SH from a palette of at most 4096 (k-means), and "
                               "orders the splats along a Morton curve");
    if (result.output_format == "compressed-ply")
        result.notes.push_back("compressed-ply rounds every value within its chunk of 256 splats (and SH to 8 bits) "
                               "and orders the splats along a Morton curve");
    return result;
}

}  // namespace vksplat::jobs
