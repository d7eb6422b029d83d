// vksplat devices: lists the Vulkan devices and whether vksplat can use them.
#include <cstdio>

#include "commands.hpp"

namespace vksplat::cli {

void register_devices(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("devices", "list Vulkan devices");
    command->footer("Example:\n  vksplat devices");
    command->callback([&action] {
        action = [] {
            for (const auto& d : gpu::list_devices()) {
                std::printf("[%u] %s (%s), subgroup %u (min %u), %.1f GiB device-local (%.1f GiB free to use), "
                            "float atomics %s (gradient sums: %s), driver %s%s%s\n",
                            d.index, d.name.c_str(), d.type_name().c_str(), d.subgroup_size, d.min_subgroup_size,
                            double(d.device_local_bytes) / (1 << 30), double(d.device_local_budget) / (1 << 30),
                            d.float_atomics ? "yes" : "no", d.float_atomics ? "atomic add" : "compare-and-swap",
                            d.driver.c_str(), d.usable ? "" : " — unusable: ",
                            d.unusable_reason.c_str());
            }
            return 0;
        };
    });
}

}  // namespace vksplat::cli
