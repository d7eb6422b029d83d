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

void register_devices(CLI::App& app, Action& action);
void register_info(CLI::App& app, Action& action);
void register_render(CLI::App& app, Action& action);
void register_demo(CLI::App& app, Action& action);
void register_prune(CLI::App& app, Action& action);
void register_cluster(CLI::App& app, Action& action);

}  // namespace vksplat::cli
