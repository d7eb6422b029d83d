#include "gpu/prefix_scan.hpp"

#include <algorithm>
#include <stdexcept>

#include "shaders/sort/scan_lookback.kernel.hpp"
#include "shaders/sort/scan_setup.kernel.hpp"

namespace vksplat::gpu {
namespace {

// Specialisation constants of the scan kernel: workgroup size, items per invocation, the most
// subgroups a workgroup can have (which sizes the shared array of subgroup partials) and the polls
// of an unpublished predecessor before a block sums it itself (a predecessor that runs publishes
// within about one block's load and scan).
std::vector<uint32_t> scan_constants(const Context& context, uint32_t lookback_spins) {
    const uint32_t min_subgroup = std::max(1u, context.info().min_subgroup_size);
    return {PrefixScan::workgroup_size, PrefixScan::items_per_thread,
            std::max(1u, PrefixScan::workgroup_size / min_subgroup), lookback_spins};
}

}  // namespace

uint64_t PrefixScan::Scratch::bytes_for(const Context&, uint32_t max_count) {
    return (VkDeviceSize(lookback_offset) + (VkDeviceSize(max_count) + block_size - 1) / block_size + 1) * sizeof(uint32_t);
}

PrefixScan::Scratch::Scratch(const Context& context, uint32_t max_count)
    : capacity_(max_count), buffer_(context, bytes_for(context, max_count), MemoryKind::device, "prefix scan scratch") {}

PrefixScan::PrefixScan(const Context& context, uint32_t lookback_spins) {
    setup_ = std::make_unique<Kernel<shader::sort::ScanSetupKernel>>(context);
    scan_ = std::make_unique<Kernel<shader::sort::ScanLookbackKernel>>(context, scan_constants(context, lookback_spins));
}

PrefixScan::~PrefixScan() = default;

void PrefixScan::record_setup(CommandStream& stream, VkDeviceAddress count_address, Scratch& scratch) const {
    stream.dispatch(*setup_,
                    {.count = count_address,
                     .control = scratch.buffer().address(),
                     .capacity = scratch.capacity(),
                     .block = block_size},
                    1);
}

void PrefixScan::record(CommandStream& stream, VkDeviceAddress input, VkDeviceAddress output,
                        VkDeviceAddress total_address, Scratch& scratch, VkDeviceAddress gather) const {
    // A block that sums an unpublished predecessor itself reads that block's input, which the
    // predecessor may be overwriting if output were input.
    if (input == output) throw std::invalid_argument("PrefixScan: input and output must differ (no scan in place)");
    stream.dispatch_indirect(*scan_,
                             {.input_values = input,
                              .gather = gather,
                              .output_values = output,
                              .control = scratch.buffer().address(),
                              .total = total_address},
                             scratch.buffer(), 0);
}

}  // namespace vksplat::gpu
