#include "gpu/radix_sort.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "shaders/radix_histogram.spv.h"
#include "shaders/radix_scan_histogram.spv.h"
#include "shaders/radix_scatter.spv.h"
#include "shaders/radix_setup.spv.h"

namespace vksplat::gpu {
namespace {

constexpr uint32_t kMaxDigitBits = 8;
constexpr uint32_t kRadixMax = 1u << kMaxDigitBits;
constexpr uint32_t kItemsPerThread = 16;
// The scatter keeps a count per digit and subgroup in shared memory (256 x subgroups x 4 bytes)
// beside the staged block (workgroup size x 16 x 4 bytes) and 1 KiB of per-digit offsets: at most
// 16 subgroups of a 128-invocation workgroup makes that 16 + 8 + 1 KiB, inside the 32 KiB that
// lavapipe (subgroups of 8) offers. With subgroups of 32 it is 4 + 8 + 1 KiB.
constexpr uint32_t kMaxSubgroupsPerGroup = 16;

struct Config {
    uint32_t workgroup_size;
    uint32_t max_subgroups;
    uint32_t block_size() const { return workgroup_size * kItemsPerThread; }
};

Config config_for(const DeviceInfo& info) {
    const uint32_t min_subgroup = std::max(1u, info.min_subgroup_size);
    const uint32_t subgroup = std::max(min_subgroup, info.subgroup_size);
    // 128 invocations (the most Vulkan guarantees), fewer when subgroups can be tiny, never fewer
    // than one subgroup.
    const uint32_t workgroup = std::max(std::min(128u, kMaxSubgroupsPerGroup * min_subgroup), subgroup);
    return {workgroup, std::max(1u, workgroup / min_subgroup)};
}

uint32_t blocks_for(uint32_t count, uint32_t block) {
    return static_cast<uint32_t>((uint64_t(count) + block - 1) / block);
}

struct SetupPush {
    VkDeviceAddress count;
    VkDeviceAddress control;
    uint32_t capacity;
    uint32_t block;
};

struct HistogramPush {
    VkDeviceAddress keys;
    VkDeviceAddress histogram;
    VkDeviceAddress control;
    VkDeviceAddress totals;
    uint32_t shift;
    uint32_t bits;
};

struct ScanHistogramPush {
    VkDeviceAddress histogram;
    VkDeviceAddress control;
    VkDeviceAddress totals;
    uint32_t bits;
};

// Control buffer: 16 words written by radix_setup, then per-digit totals for each pass.
constexpr uint32_t kMaxPasses = 4;
constexpr VkDeviceSize kTotalsOffset = 64;
constexpr VkDeviceSize kTotalsBytes = VkDeviceSize(kMaxPasses) * kRadixMax * 4;

struct ScatterPush {
    VkDeviceAddress keys_in;
    VkDeviceAddress values_in;
    VkDeviceAddress keys_out;
    VkDeviceAddress values_out;
    VkDeviceAddress histogram;
    VkDeviceAddress control;
    uint32_t shift;
    uint32_t bits;
};

}  // namespace

RadixSort::Scratch::Scratch(const Context& context, uint32_t max_count)
    : capacity_(max_count),
      keys_(context, VkDeviceSize(max_count) * 4, MemoryKind::device, "radix sort keys"),
      values_(context, VkDeviceSize(max_count) * 4, MemoryKind::device, "radix sort values"),
      histogram_(context, VkDeviceSize(kRadixMax) * blocks_for(max_count, config_for(context.info()).block_size()) * 4,
                 MemoryKind::device, "radix sort histogram"),
      control_(context, kTotalsOffset + kTotalsBytes, MemoryKind::device, "radix sort control") {}

uint64_t RadixSort::Scratch::bytes_for(const Context& context, uint32_t max_count) {
    return VkDeviceSize(max_count) * 8 +
           VkDeviceSize(kRadixMax) * blocks_for(max_count, config_for(context.info()).block_size()) * 4 +
           kTotalsOffset + kTotalsBytes;
}

RadixSort::RadixSort(const Context& context) {
    const Config config = config_for(context.info());
    block_size_ = config.block_size();
    setup_ = std::make_unique<ComputePipeline>(context, radix_setup_spv, sizeof(SetupPush), std::vector<uint32_t>{},
                                               "radix_setup");
    histogram_ = std::make_unique<ComputePipeline>(context, radix_histogram_spv, sizeof(HistogramPush),
                                                   std::vector<uint32_t>{config.workgroup_size, kItemsPerThread},
                                                   "radix_histogram");
    scan_histogram_ = std::make_unique<ComputePipeline>(
        context, radix_scan_histogram_spv, sizeof(ScanHistogramPush),
        std::vector<uint32_t>{config.workgroup_size, kItemsPerThread, config.max_subgroups}, "radix_scan_histogram");
    scatter_ = std::make_unique<ComputePipeline>(
        context, radix_scatter_spv, sizeof(ScatterPush),
        std::vector<uint32_t>{config.workgroup_size, kItemsPerThread, config.max_subgroups}, "radix_scatter");
}

RadixSort::~RadixSort() = default;

uint32_t RadixSort::passes_for(uint32_t key_bits) {
    // Passes of at most 8 bits, an even number of them (so the ping-pong ends where it began).
    uint32_t passes = (key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
    return passes + passes % 2;
}

void RadixSort::record(CommandStream& stream, const Buffer& keys, const Buffer& values,
                       VkDeviceAddress count_address, uint32_t key_bits, Scratch& scratch) const {
    if (key_bits < 1 || key_bits > 32)
        throw std::invalid_argument("RadixSort: key_bits must be 1..32, not " + std::to_string(key_bits));
    // Bits spread as evenly as possible over the passes: the first `extra` passes take base + 1
    // bits, the rest base bits (possibly 0: a stable copy).
    const uint32_t passes = passes_for(key_bits);
    const uint32_t base = key_bits / passes;
    const uint32_t extra = key_bits % passes;

    const uint64_t capacity = std::min<uint64_t>({scratch.capacity(), keys.size() / 4, values.size() / 4});
    const VkDeviceAddress control = scratch.control_.address();
    stream.fill(scratch.control_, 0, kTotalsOffset, kTotalsBytes);
    stream.dispatch(*setup_,
                    SetupPush{count_address, control, static_cast<uint32_t>(capacity), block_size_},
                    1);
    stream.barrier();

    const Buffer* source_keys = &keys;
    const Buffer* source_values = &values;
    const Buffer* target_keys = &scratch.keys_;
    const Buffer* target_values = &scratch.values_;
    uint32_t shift = 0;
    for (uint32_t pass = 0; pass < passes; ++pass) {
        const uint32_t bits = base + (pass < extra ? 1 : 0);
        const VkDeviceAddress totals = control + kTotalsOffset + VkDeviceSize(pass) * kRadixMax * 4;
        stream.dispatch_indirect(*histogram_,
                                 HistogramPush{source_keys->address(), scratch.histogram_.address(), control, totals,
                                               shift, bits},
                                 scratch.control_, 0);
        stream.barrier();
        stream.dispatch(*scan_histogram_, ScanHistogramPush{scratch.histogram_.address(), control, totals, bits},
                        1u << bits);
        stream.barrier();
        stream.dispatch_indirect(*scatter_,
                                 ScatterPush{source_keys->address(), source_values->address(), target_keys->address(),
                                             target_values->address(), scratch.histogram_.address(), control, shift,
                                             bits},
                                 scratch.control_, 0);
        if (pass + 1 < passes) stream.barrier();
        std::swap(source_keys, target_keys);
        std::swap(source_values, target_values);
        shift += bits;
    }
}

}  // namespace vksplat::gpu
