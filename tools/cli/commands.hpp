#pragma once
// Each subcommand lives in its own file and registers itself on the app; main() only wires them.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "vksplat/gpu/context.hpp"

namespace vksplat::cli {

// The command a parsed subcommand runs; returns the process exit code.
using Action = std::function<int()>;

// Options every GPU command shares.
struct GpuOptions {
    std::string device;
    bool validation = false;
    gpu::ContextOptions context_options() const { return {device, validation}; }
};
void add_gpu_options(CLI::App& command, GpuOptions& options);

// Parses argv and runs the action of the chosen subcommand, reporting errors; the exit code.
int run_cli(CLI::App& app, const Action& action, int argc, char** argv);

void register_devices(CLI::App& app, Action& action);
void register_info(CLI::App& app, Action& action);
void register_render(CLI::App& app, Action& action);
void register_demo(CLI::App& app, Action& action);
void register_prune(CLI::App& app, Action& action);
void register_bench(CLI::App& app, Action& action);
void register_convert(CLI::App& app, Action& action);
void register_view(CLI::App& app, Action& action);
void register_sweep(CLI::App& app, Action& action);
void register_cluster(CLI::App& app, Action& action);

}  // namespace vksplat::cli
