// vksplat view: an interactive window on a scene (tools/viewer/), when built with VKSPLAT_VIEWER.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "number_checks.hpp"
#include "vksplat/error.hpp"
#ifdef VKSPLAT_HAS_VIEWER
#include "viewer.hpp"
#endif

namespace vksplat::cli {
namespace {

struct ViewArgs {
    std::string scene, cameras, compare, size = "1024x768";
    std::vector<double> up;
    std::vector<float> background{0, 0, 0};
    bool validation = false, no_hud = false;
};

int run_view(const ViewArgs& args) {
#ifdef VKSPLAT_HAS_VIEWER
    viewer::ViewerOptions options;
    options.scene = args.scene;
    options.cameras = args.cameras;
    options.compare = args.compare;
    if (!args.up.empty()) options.up = std::array<double, 3>{args.up[0], args.up[1], args.up[2]};
    if (std::sscanf(args.size.c_str(), "%dx%d", &options.width, &options.height) != 2 || options.width < 1 ||
        options.height < 1)
        throw InputError("--size", "'" + args.size + "' is not WIDTHxHEIGHT");
    options.background = {args.background[0], args.background[1], args.background[2]};
    options.validation = args.validation;
    options.hud = !args.no_hud;
    return viewer::run_viewer(options);
#else
    (void)args;
    std::fprintf(stderr, "vksplat: this build has no viewer: GLFW was not found when it was configured "
                         "(install libglfw3-dev and configure again, or set -DVKSPLAT_VIEWER=ON)\n");
    return 1;
#endif
}

}  // namespace

void register_view(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("view", "look at a scene in a window");
    command->footer(
        "Mouse: left drag turns (orbit about the focus point, or the view in fly mode), right or shift+left\n"
        "drag pans, wheel zooms. Keys: Tab or F switches orbit/fly, W A S D Q E fly, N/right and P/left step\n"
        "through the dataset cameras, Space flies through them, V shows their frustums, B shows the --compare\n"
        "scene and back, +/- zoom, 0-3 SH degree, C screenshot (vksplat_view_NNN.png in the current\n"
        "folder, never replacing a file), H lists the keys in the HUD (and again hides it), Esc quits. The HUD and\n"
        "the title show the counts, SH degree and frame time.\n"
        "Without --cameras, a cameras.json beside the scene (a trainer's output folder) gives the up direction\n"
        "and the dataset cameras.\n"
        "Example:\n  vksplat view point_cloud.ply --cameras cameras.json");
    auto args = std::make_shared<ViewArgs>();
    command->add_option("scene", args->scene, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->add_option("--cameras", args->cameras, "cameras.json, transforms.json or a COLMAP sparse folder")
        ->check(CLI::ExistingPath);
    command->add_option("--compare", args->compare,
                        "a second scene (e.g. a pruned copy) that B switches to and back, from the same view")
        ->check(CLI::ExistingFile);
    command->add_option("--up", args->up, "the world's up direction X,Y,Z (default: from the cameras, or those of a cameras.json beside the scene, else +z)")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in());
    command->add_option("--size", args->size, "window size WIDTHxHEIGHT");
    command->add_option("--background", args->background, "background colour R,G,B in [0,1]")
        ->delimiter(',')
        ->expected(3)
        ->check(number_in(0.0, 1.0));
    command->add_flag("--no-hud", args->no_hud, "start without the HUD (counts, SH degree, frame time; H brings it back)");
    command->add_flag("--validation", args->validation, "enable Vulkan validation layers (slow; for debugging)");
    command->callback([&action, args] { action = [args] { return run_view(*args); }; });
}

}  // namespace vksplat::cli
