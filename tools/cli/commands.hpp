#pragma once
// Each subcommand lives in its own file and registers itself on the app; main() only wires them.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "vksplat/gpu/context.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::cli {

// The command a parsed subcommand runs; returns the process exit code.
using Action = std::function<int()>;

// Options every GPU command shares.
struct GpuOptions {
    std::string device;
    bool validation = false;
    double memory_budget_mb = 0;  // --memory-budget: 0 is the device's own limit
    gpu::ContextOptions context_options() const {
        return {device, validation, static_cast<uint64_t>(memory_budget_mb * 1048576.0)};
    }
};
void add_gpu_options(CLI::App& command, GpuOptions& options);
// How train, finetune and prune --recover sum gradients: in fixed point (the same bytes every run)
// wherever the device can (train::deterministic_by_default), unless --fast-sums; --deterministic
// insists, and is refused by name where the device cannot.
struct GradientSumsArgs {
    bool deterministic = false, fast_sums = false;
    bool fixed_point(const gpu::Context& context) const;
};
// Registers --deterministic and --fast-sums (excluding each other), their help starting with
// `condition` (e.g. "with --recover: "); returns both, for commands whose other options they need.
std::pair<CLI::Option*, CLI::Option*> add_gradient_sums_flags(CLI::App& command, GradientSumsArgs& args,
                                                              const std::string& condition = "");
// Tracks the most depth-ordered chunks any frame needed (--memory-budget) and says so once.
struct ChunkReport {
    uint32_t most = 1;
    void saw(uint32_t chunks) { most = std::max(most, chunks); }
    void print(const gpu::Context& context) const;
};

// Reads a scene file in any format vksplat reads (io::read_scene: by extension, and the header for
// .ply), printing the reader's notes (ignored properties, skipped data) on stderr as "note: ...".
GaussianCloud read_scene_file(const std::string& path);

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
void register_finetune(CLI::App& app, Action& action);
void register_train(CLI::App& app, Action& action);

}  // namespace vksplat::cli
