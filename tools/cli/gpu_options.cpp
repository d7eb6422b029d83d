// Options every GPU command shares; in its own file so that the GPU-host benchmark binary, which
// registers only `bench`, links it without the rest of the CLI.
#include <cstdio>

#include "commands.hpp"
#include "number_checks.hpp"

namespace vksplat::cli {

void add_gpu_options(CLI::App& command, GpuOptions& options) {
    command.add_option("--device", options.device,
                       "GPU to use: index or part of its name (default: first discrete GPU, else any)");
    command.add_flag("--validation", options.validation, "enable Vulkan validation layers (slow; for debugging)");
    command.add_option("--memory-budget", options.memory_budget_mb,
                       "device memory to use, in MiB (default: the device's limit); frames that do not fit are "
                       "rendered in depth-ordered chunks, with the same picture")
        // Below a kilobyte the budget rounds to nothing (0 bytes, which means no budget), and no
        // frame fits in it anyway; above 1e9 MiB it would overflow the byte count.
        ->check(number_in(0.001, 1e9));
}

void ChunkReport::print(const gpu::Context& context) const {
    if (most > 1)
        std::fprintf(stderr, "memory budget %.0f MiB: frames rendered in up to %u depth-ordered chunks\n",
                     double(context.memory_budget()) / 1048576.0, most);
}

}  // namespace vksplat::cli
