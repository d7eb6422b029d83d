// vksplat_bench: `vksplat bench` alone, for GPU hosts that have a Vulkan driver and little else.
// The same code as the CLI's subcommand (tools/cli/bench.cpp); linked so that it needs no image
// codecs (see CMakeLists.txt here).
#include "commands.hpp"

int main(int argc, char** argv) {
    using namespace vksplat::cli;
    CLI::App app{"vksplat_bench: GPU time per frame and per stage (vksplat bench)"};
    app.require_subcommand(1);
    Action action;
    register_bench(app, action);
    return run_cli(app, action, argc, argv);
}
