// vksplat convert: rewrites a scene file in another format.
#include <cstdio>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/convert_scene.hpp"

namespace vksplat::cli {
namespace {

struct ConvertArgs {
    std::string input, output, input_format, output_format;
    std::vector<int> sh_bits;  // degree 1, then degrees 2 and 3; empty: full precision
    bool force = false;
};

int run_convert(const ConvertArgs& args) {
    jobs::ConvertOptions options;
    options.input_format = args.input_format;
    options.output_format = args.output_format;
    options.mode = args.force ? io::WriteMode::overwrite : io::WriteMode::refuse_existing;
    if (!args.sh_bits.empty()) options.sh_precision = prune::ShPrecision{args.sh_bits[0], args.sh_bits[1]};
    const auto result = jobs::convert_scene(args.input, args.output, options);
    for (const auto& note : result.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    std::printf("wrote %zu Gaussians (SH degree %d) from %s (%s) to %s (%s)\n", result.gaussians,
                result.output_sh_degree, args.input.c_str(), result.input_format.c_str(), args.output.c_str(),
                result.output_format.c_str());
    return 0;
}

}  // namespace

void register_convert(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("convert", "rewrite a scene file in another format");
    command->footer(
        "Formats: ply (INRIA 3DGS), compressed-ply (PlayCanvas, *.compressed.ply), splat (antimatter15),\n"
        "spz (Niantic; written as version 3, or 4 with --format spz-v4), sog (PlayCanvas SOG: a .sog zip,\n"
        "or a folder's meta.json beside its WebP textures) and gltf (binary glTF, .glb, with\n"
        "KHR_gaussian_splatting) are read and written; gsplat-pt\n"
        "(gsplat checkpoint) is read only. The extension picks the format unless --format (output) or\n"
        "--input-format names it; a .ply is read as its header says.\n"
        "Example:\n  vksplat convert point_cloud.ply scene.spz\n  vksplat convert point_cloud.ply scene.compressed.ply\n"
        "  vksplat convert point_cloud.ply scene.sog\n"
        "  vksplat convert ckpt_29999.pt scene.ply --force");
    auto args = std::make_shared<ConvertArgs>();
    std::string formats;
    for (const auto& f : io::scene_formats()) formats += (formats.empty() ? "" : ", ") + f;
    command->add_option("input", args->input, "scene file to read")->required()->check(CLI::ExistingFile);
    command->add_option("output", args->output, "scene file to write")->required();
    command->add_option("-f,--format", args->output_format, "output format (" + formats + ")");
    command->add_option("--input-format", args->input_format, "input format, if its extension does not say");
    command->add_option("--sh-bits", args->sh_bits,
                        "B1,B2: round the higher SH to B1 bits of SPZ's byte for degree 1 and B2 for degrees 2 "
                        "and 3 (1..8; Niantic's encoder: 5,4), for a smaller SPZ (see prune --sh-bits)")
        ->delimiter(',')
        ->expected(2);
    command->add_flag("--force", args->force, "overwrite the output file if it exists");
    command->callback([&action, args] { action = [args] { return run_convert(*args); }; });
}

}  // namespace vksplat::cli
