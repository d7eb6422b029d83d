// Options every GPU command shares; in its own file so that the GPU-host benchmark binary, which
// registers only `bench`, links it without the rest of the CLI.
#include "commands.hpp"

namespace vksplat::cli {

void add_gpu_options(CLI::App& command, GpuOptions& options) {
    command.add_option("--device", options.device,
                       "GPU to use: index or part of its name (default: first discrete GPU, else any)");
    command.add_flag("--validation", options.validation, "enable Vulkan validation layers (slow; for debugging)");
}

}  // namespace vksplat::cli
