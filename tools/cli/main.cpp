// vksplat: render and compact 3D Gaussian Splatting scenes with Vulkan compute.
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "vksplat/error.hpp"

namespace vksplat::cli {

void add_gpu_options(CLI::App& command, GpuOptions& options) {
    command.add_option("--device", options.device,
                       "GPU to use: index or part of its name (default: first discrete GPU, else any)");
    command.add_flag("--validation", options.validation, "enable Vulkan validation layers (slow; for debugging)");
}

}  // namespace vksplat::cli

int main(int argc, char** argv) {
    using namespace vksplat::cli;
    CLI::App app{"vksplat: render and compact 3D Gaussian Splatting scenes with Vulkan compute"};
    app.footer("Example:\n  vksplat demo --out demo_out\n  vksplat render scene.ply --cameras cameras.json --out renders");
    app.require_subcommand(1);
    Action action;
    register_devices(app, action);
    register_info(app, action);
    register_render(app, action);
    register_demo(app, action);
    register_prune(app, action);
    register_cluster(app, action);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        return action();
    } catch (const vksplat::InputError& e) {
        std::fprintf(stderr, "vksplat: error: %s\n", e.what());
        return 2;
    } catch (const vksplat::GpuError& e) {
        std::fprintf(stderr, "vksplat: GPU error: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vksplat: error: %s\n", e.what());
        return 1;
    }
}
