#include "gpu/radix_sort.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "shaders/sort/radix_block_histogram.kernel.hpp"
#include "shaders/sort/radix_histogram.kernel.hpp"
#include "shaders/sort/radix_scan_histogram.kernel.hpp"
#include "shaders/sort/radix_scatter.kernel.hpp"
#include "shaders/sort/radix_scatter_one_sweep.kernel.hpp"
#include "shaders/sort/radix_setup.kernel.hpp"

namespace vksplat::gpu {
namespace {

using namespace shader::sort;

constexpr uint32_t kMaxDigitBits = 8;
constexpr uint32_t kRadixMax = RADIX_MAX;
static_assert(kRadixMax == 1u << kMaxDigitBits);
constexpr uint32_t kMaxPasses = MAX_PASSES;
constexpr uint32_t kItemsPerThread = 16;
// Per digit, the scatter keeps a count per subgroup (the ranking loops over them), so subgroups
// per workgroup are capped.
constexpr uint32_t kMaxSubgroupsPerGroup = 16;
// Sorts of at most this many blocks run one sweep per pass: one histogram kernel for all passes,
// then one scatter kernel per pass that learns the earlier blocks' digit counts by look-back. A
// block's look-back reads 1 KiB per predecessor back to the nearest one that knows its running
// totals, so the traffic grows with the square of the blocks running at once; larger sorts make
// three kernels per pass (block histogram, its scan, scatter) instead. On an H100 one sweep was
// faster at 120 blocks (lego's depth sort: 0.118 vs 0.135 ms) and slower at 309 (0.081 vs 0.074).
constexpr uint32_t kOneSweepMaxBlocks = 192;

// Shared memory of a scatter workgroup (radix_block.glsl, radix_scatter_one_sweep.comp): the staged
// block, a count per digit and subgroup, and per digit its displacement and fallback count.
uint32_t scatter_shared_bytes(uint32_t workgroup, uint32_t min_subgroup) {
    return (workgroup * kItemsPerThread + workgroup / min_subgroup * kRadixMax + 2 * kRadixMax) * 4;
}

struct Config {
    uint32_t workgroup_size;
    uint32_t max_subgroups;
    uint32_t block_size() const { return workgroup_size * kItemsPerThread; }
};

// The widest workgroup of 256 or 128 invocations that the device runs, whose subgroups are at
// most kMaxSubgroupsPerGroup and whose scatter fits in shared memory; never less than one
// subgroup. Wider workgroups make blocks of more keys for the same work per invocation, so a sort
// has fewer blocks: a one-sweep pass waits on a look-back chain as long as its block count, and
// sorts of up to twice the keys run one sweep. On an H200 (subgroups of 32, 26 KiB for 256), 256
// instead of 128: snowmiku's frame 0.373 -> 0.346 ms, lego 90% dropped 0.220 -> 0.206, bonsai
// 0.407 -> 0.374 (its 400 k depth keys now one sweep: 0.115 -> 0.077). 128 invocations with 32
// keys each (the same block) was slower than 128 x 16: the ranking is serial per invocation.
// lavapipe (subgroups of 8): 128 invocations, 16 subgroups, 26 KiB of its 32.
Config config_for(const DeviceInfo& info) {
    const uint32_t min_subgroup = std::max(1u, info.min_subgroup_size);
    const uint32_t subgroup = std::max(min_subgroup, info.subgroup_size);
    uint32_t workgroup = 128;
    if (256 <= info.max_workgroup_invocations && 256 / min_subgroup <= kMaxSubgroupsPerGroup &&
        scatter_shared_bytes(256, min_subgroup) <= info.max_shared_memory_bytes)
        workgroup = 256;
    workgroup = std::max(std::min(workgroup, kMaxSubgroupsPerGroup * min_subgroup), subgroup);
    return {workgroup, std::max(1u, workgroup / min_subgroup)};
}

uint32_t blocks_for(uint32_t count, uint32_t block) {
    return static_cast<uint32_t>((uint64_t(count) + block - 1) / block);
}

// Control buffer: 16 words written by radix_setup, then per-pass digit totals.
constexpr VkDeviceSize kTotalsOffset = RADIX_TOTALS * 4;
constexpr VkDeviceSize kTotalsBytes = VkDeviceSize(kMaxPasses) * kRadixMax * 4;
constexpr VkDeviceSize kControlBytes = kTotalsOffset + kTotalsBytes;

// The per-block words: look-back words of every pass for one-sweep sorts, one pass's histogram
// for larger ones.
VkDeviceSize block_words_bytes(uint32_t count, uint32_t block) {
    const uint64_t blocks = blocks_for(count, block);
    return std::max(VkDeviceSize(kRadixMax) * blocks,
                    VkDeviceSize(kMaxPasses) * kRadixMax * std::min<uint64_t>(blocks, kOneSweepMaxBlocks)) *
           4;
}

}  // namespace

RadixSort::Scratch::Scratch(const Context& context, uint32_t max_count)
    : capacity_(max_count),
      keys_(context, VkDeviceSize(max_count) * 4, MemoryKind::device, "radix sort keys"),
      values_(context, VkDeviceSize(max_count) * 4, MemoryKind::device, "radix sort values"),
      block_words_(context, block_words_bytes(max_count, config_for(context.info()).block_size()),
                   MemoryKind::device, "radix sort block words"),
      control_(context, kControlBytes, MemoryKind::device, "radix sort control") {}

uint64_t RadixSort::Scratch::bytes_for(const Context& context, uint32_t max_count) {
    return VkDeviceSize(max_count) * 8 + block_words_bytes(max_count, config_for(context.info()).block_size()) +
           kControlBytes;
}

// A predecessor that runs publishes within about one block's ranking time (the default spins cover
// that); one that never got to run would otherwise stall the chain.
RadixSort::RadixSort(const Context& context, uint32_t lookback_spins) {
    const Config config = config_for(context.info());
    block_size_ = config.block_size();
    setup_ = std::make_unique<Kernel<RadixSetupKernel>>(context);
    histogram_ = std::make_unique<Kernel<RadixHistogramKernel>>(
        context, std::vector<uint32_t>{config.workgroup_size, kItemsPerThread});
    block_histogram_ = std::make_unique<Kernel<RadixBlockHistogramKernel>>(
        context, std::vector<uint32_t>{config.workgroup_size, kItemsPerThread});
    scan_histogram_ = std::make_unique<Kernel<RadixScanHistogramKernel>>(
        context, std::vector<uint32_t>{config.workgroup_size, kItemsPerThread, config.max_subgroups});
    one_sweep_scatter_ = std::make_unique<Kernel<RadixScatterOneSweepKernel>>(
        context,
        std::vector<uint32_t>{config.workgroup_size, kItemsPerThread, config.max_subgroups, lookback_spins});
    scatter_ = std::make_unique<Kernel<RadixScatterKernel>>(
        context, std::vector<uint32_t>{config.workgroup_size, kItemsPerThread, config.max_subgroups});
}

RadixSort::~RadixSort() = default;

uint32_t RadixSort::block_size_for(const DeviceInfo& info) { return config_for(info).block_size(); }

uint32_t RadixSort::passes_for(uint32_t key_bits) {
    // Passes of at most 8 bits, an even number of them (so the ping-pong ends where it began).
    uint32_t passes = (key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
    return passes + passes % 2;
}

uint64_t RadixSort::capacity(const Buffer& keys, const Buffer& values, const Scratch& scratch) {
    return std::min<uint64_t>({scratch.capacity(), keys.size() / 4, values.size() / 4});
}

bool RadixSort::one_sweep(uint64_t capacity) const {
    return blocks_for(static_cast<uint32_t>(capacity), block_size_) <= kOneSweepMaxBlocks;
}

void RadixSort::record_setup(CommandStream& stream, const Buffer& keys, const Buffer& values,
                             VkDeviceAddress count_address, Scratch& scratch) const {
    stream.dispatch(*setup_,
                    {.count = count_address,
                     .control = scratch.control_.address(),
                     .capacity = static_cast<uint32_t>(capacity(keys, values, scratch)),
                     .block = block_size_},
                    1);
}

RadixSort::DigitCounting RadixSort::digits_for(uint32_t key_bits) {
    if (key_bits < 1 || key_bits > 32)
        throw std::invalid_argument("RadixSort: key_bits must be 1..32, not " + std::to_string(key_bits));
    // Bits spread as evenly as possible over the passes: the first `extra` passes take base + 1
    // bits, the rest base bits (possibly 0: a stable copy).
    DigitCounting layout{};
    layout.passes = passes_for(key_bits);
    const uint32_t base = key_bits / layout.passes;
    const uint32_t extra = key_bits % layout.passes;
    for (uint32_t pass = 0, shift = 0; pass < layout.passes; ++pass) {
        const uint32_t bits = base + (pass < extra ? 1 : 0);
        layout.digits[pass] = shift | bits << 8;
        shift += bits;
    }
    return layout;
}

std::optional<RadixSort::DigitCounting> RadixSort::record_host_setup(CommandStream& stream, const Buffer& keys,
                                                                     const Buffer& values, uint32_t count,
                                                                     uint32_t key_bits, Scratch& scratch) const {
    DigitCounting counting = digits_for(key_bits);
    const uint64_t held = capacity(keys, values, scratch);
    if (!one_sweep(held)) return std::nullopt;
    // What radix_setup would write, the control words and zero totals, in one buffer update (fills
    // of the totals and look-back words at a frame's start cost a few microseconds of its chain on
    // an H200; small updates did not); the producer empties the look-back words, as the histogram
    // kernel would.
    const uint32_t clamped = static_cast<uint32_t>(std::min<uint64_t>(count, held));
    const uint32_t blocks = blocks_for(clamped, block_size_);
    std::array<uint32_t, kControlBytes / 4> control{};
    control[0] = std::min(blocks, shader::MAX_GROUPS_X);
    control[1] = control[2] = 1;
    control[3] = clamped;
    control[4] = blocks;
    stream.update(scratch.control_, control.data(), kControlBytes);
    counting.totals = scratch.control_.address() + kTotalsOffset;
    counting.lookback = scratch.block_words_.address();
    counting.lookback_words = blocks * kMaxPasses * kRadixMax;
    return counting;
}

void RadixSort::record(CommandStream& stream, const Buffer& keys, const Buffer& values, uint32_t key_bits,
                       Scratch& scratch, bool digits_counted) const {
    const DigitCounting layout = digits_for(key_bits);
    const uint32_t passes = layout.passes;
    uint32_t shifts[kMaxPasses] = {}, bits[kMaxPasses] = {};
    for (uint32_t pass = 0; pass < passes; ++pass) {
        shifts[pass] = layout.digits[pass] & 0xffu;
        bits[pass] = layout.digits[pass] >> 8;
    }

    const bool sweep = one_sweep(capacity(keys, values, scratch));
    if (digits_counted && !sweep)
        throw std::logic_error("RadixSort: digits counted by their producer, but the sort does not run one sweep");
    const VkDeviceAddress control = scratch.control_.address();
    const VkDeviceAddress block_words = scratch.block_words_.address();
    if (sweep && !digits_counted) {
        RadixHistogramPush histogram{.keys = keys.address(),
                                     .lookback = block_words,
                                     .control = control,
                                     .totals = control + kTotalsOffset,
                                     .digits = {},
                                     .passes = passes};
        for (uint32_t pass = 0; pass < passes; ++pass) histogram.digits[pass] = layout.digits[pass];
        stream.dispatch_indirect(*histogram_, histogram, scratch.control_, 0);
        stream.barrier();
    }

    const Buffer* source_keys = &keys;
    const Buffer* source_values = &values;
    const Buffer* target_keys = &scratch.keys_;
    const Buffer* target_values = &scratch.values_;
    for (uint32_t pass = 0; pass < passes; ++pass) {
        const VkDeviceAddress totals = control + kTotalsOffset + VkDeviceSize(pass) * kRadixMax * 4;
        if (!sweep) {
            stream.dispatch_indirect(*block_histogram_,
                                     {.keys = source_keys->address(),
                                      .hist = block_words,
                                      .control = control,
                                      .totals = totals,
                                      .shift = shifts[pass],
                                      .bits = bits[pass]},
                                     scratch.control_, 0);
            stream.barrier();
            stream.dispatch(*scan_histogram_,
                            {.hist = block_words, .control = control, .totals = totals, .bits = bits[pass]},
                            1u << bits[pass]);
            stream.barrier();
        }
        if (sweep)
            stream.dispatch_indirect(*one_sweep_scatter_,
                                     {.keys_in = source_keys->address(),
                                      .values_in = source_values->address(),
                                      .keys_out = target_keys->address(),
                                      .values_out = target_values->address(),
                                      .lookback = block_words,
                                      .control = control,
                                      .totals = totals,
                                      .pass = pass,
                                      .shift = shifts[pass],
                                      .bits = bits[pass]},
                                     scratch.control_, 0);
        else
            stream.dispatch_indirect(*scatter_,
                                     {.keys_in = source_keys->address(),
                                      .values_in = source_values->address(),
                                      .keys_out = target_keys->address(),
                                      .values_out = target_values->address(),
                                      .hist = block_words,
                                      .control = control,
                                      .shift = shifts[pass],
                                      .bits = bits[pass]},
                                     scratch.control_, 0);
        if (pass + 1 < passes) stream.barrier();
        std::swap(source_keys, target_keys);
        std::swap(source_values, target_values);
    }
}

}  // namespace vksplat::gpu
