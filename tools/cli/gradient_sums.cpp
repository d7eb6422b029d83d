#include "commands.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::cli {

bool GradientSumsArgs::fixed_point(const gpu::Context& context) const {
    return train::fixed_point_sums(context, deterministic, fast_sums);
}

std::pair<CLI::Option*, CLI::Option*> add_gradient_sums_flags(CLI::App& command, GradientSumsArgs& args,
                                                              const std::string& condition) {
    CLI::Option* deterministic = command.add_flag(
        "--deterministic", args.deterministic,
        condition + "sum gradients in fixed point so that the same inputs give the same bytes every run (the "
                    "default where the device has 64-bit atomics; with this flag, refused where it has not)");
    CLI::Option* fast_sums =
        command
            .add_flag("--fast-sums", args.fast_sums,
                      condition + "sum gradients with float atomics in any order: up to 9% less GPU time per step, "
                                  "but two runs differ")
            ->excludes(deterministic);
    return {deterministic, fast_sums};
}

}  // namespace vksplat::cli
