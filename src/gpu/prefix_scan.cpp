#include "gpu/prefix_scan.hpp"

#include <algorithm>

#include "shaders/scan_blocks.spv.h"
#include "shaders/scan_downsweep.spv.h"
#include "shaders/scan_reduce.spv.h"
#include "shaders/scan_setup.spv.h"

namespace vksplat::gpu {
namespace {

struct SetupPush {
    VkDeviceAddress count;
    VkDeviceAddress control;
    uint32_t capacity;
    uint32_t block;
};

struct ReducePush {
    VkDeviceAddress input;
    VkDeviceAddress control;
};

struct BlocksPush {
    VkDeviceAddress control;
    VkDeviceAddress total;
};

struct DownsweepPush {
    VkDeviceAddress input;
    VkDeviceAddress output;
    VkDeviceAddress control;
};

// Specialisation constants of the per-block kernels: workgroup size, items per invocation and the
// most subgroups a workgroup can have (which sizes the shared array of subgroup partials).
std::vector<uint32_t> block_constants(const Context& context) {
    const uint32_t min_subgroup = std::max(1u, context.info().min_subgroup_size);
    return {PrefixScan::workgroup_size, PrefixScan::items_per_thread,
            std::max(1u, PrefixScan::workgroup_size / min_subgroup)};
}

}  // namespace

uint64_t PrefixScan::Scratch::bytes_for(const Context&, uint32_t max_count) {
    return (VkDeviceSize(sums_offset) + (VkDeviceSize(max_count) + block_size - 1) / block_size + 1) * sizeof(uint32_t);
}

PrefixScan::Scratch::Scratch(const Context& context, uint32_t max_count)
    : capacity_(max_count), buffer_(context, bytes_for(context, max_count), MemoryKind::device, "prefix scan scratch") {}

PrefixScan::PrefixScan(const Context& context) {
    const auto constants = block_constants(context);
    setup_ = std::make_unique<ComputePipeline>(context, scan_setup_spv, sizeof(SetupPush), std::vector<uint32_t>{},
                                               "scan_setup");
    reduce_ = std::make_unique<ComputePipeline>(context, scan_reduce_spv, sizeof(ReducePush), constants, "scan_reduce");
    blocks_ = std::make_unique<ComputePipeline>(context, scan_blocks_spv, sizeof(BlocksPush), constants, "scan_blocks");
    downsweep_ = std::make_unique<ComputePipeline>(context, scan_downsweep_spv, sizeof(DownsweepPush), constants,
                                                   "scan_downsweep");
}

PrefixScan::~PrefixScan() = default;

void PrefixScan::record(CommandStream& stream, VkDeviceAddress input, VkDeviceAddress output,
                        VkDeviceAddress count_address, VkDeviceAddress total_address, Scratch& scratch) const {
    const VkDeviceAddress control = scratch.buffer().address();
    stream.dispatch(*setup_, SetupPush{count_address, control, scratch.capacity(), block_size}, 1);
    stream.barrier();
    stream.dispatch_indirect(*reduce_, ReducePush{input, control}, scratch.buffer(), 0);
    stream.barrier();
    stream.dispatch(*blocks_, BlocksPush{control, total_address}, 1);
    stream.barrier();
    stream.dispatch_indirect(*downsweep_, DownsweepPush{input, output, control}, scratch.buffer(), 0);
}

}  // namespace vksplat::gpu
