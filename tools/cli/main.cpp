// vksplat: render and compact 3D Gaussian Splatting scenes with Vulkan compute.
#include <string>

#include "commands.hpp"
#include "vksplat/version.hpp"

int main(int argc, char** argv) {
    using namespace vksplat::cli;
    CLI::App app{"vksplat: render and compact 3D Gaussian Splatting scenes with Vulkan compute"};
    app.footer("Example:\n  vksplat demo --out demo_out\n  vksplat render scene.ply --cameras cameras.json --out renders");
    app.set_version_flag("--version", std::string("vksplat ") + vksplat::kVersion);
    app.require_subcommand(1);
    Action action;
    register_devices(app, action);
    register_info(app, action);
    register_render(app, action);
    register_demo(app, action);
    register_prune(app, action);
    register_bench(app, action);
    register_convert(app, action);
    register_view(app, action);
    register_sweep(app, action);
    register_cluster(app, action);
    register_finetune(app, action);
    register_train(app, action);
    return run_cli(app, action, argc, argv);
}
