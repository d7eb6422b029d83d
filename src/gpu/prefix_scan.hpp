#pragma once
// PrefixScan: exclusive prefix sum of uint32 values on the GPU, with the element count read from
// GPU memory (no CPU round trip): a one-workgroup setup kernel turns the count into an indirect
// dispatch size, then one kernel scans every block and chains the blocks by decoupled look-back
// (with a fallback that needs no forward-progress guarantee: scan_lookback.comp). The setup is
// recorded apart so that a frame can run it beside earlier work, as soon as the count is known:
// each kernel in a chain costs a few microseconds however little it does. Sums are exact below
// 2^30 and saturate there. Works for any subgroup size. Kernels: shaders/sort/scan_*.comp, layouts
// in shaders/sort/prefix_scan.h.
#include <cstdint>
#include <memory>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "shaders/sort/prefix_scan.h"

namespace vksplat::shader::sort {
struct ScanSetupKernel;
struct ScanLookbackKernel;
}  // namespace vksplat::shader::sort

namespace vksplat::gpu {

class PrefixScan {
public:
    static constexpr uint32_t workgroup_size = 128;
    static constexpr uint32_t items_per_thread = 16;
    static constexpr uint32_t block_size = workgroup_size * items_per_thread;  // elements per block
    // Sums from this value up are saturated: the true sum is at least this (a look-back word holds
    // a 2-bit flag and a 30-bit value).
    static constexpr uint32_t saturated_sum = (1u << 30) - 1;

    // lookback_spins: polls of an unpublished predecessor block before a block sums it itself (0
    // makes that fallback common: tests use it to check it).
    static constexpr uint32_t default_lookback_spins = 64;
    explicit PrefixScan(const Context& context, uint32_t lookback_spins = default_lookback_spins);
    ~PrefixScan();
    PrefixScan(const PrefixScan&) = delete;
    PrefixScan& operator=(const PrefixScan&) = delete;

    // Scratch memory for scans of up to max_count elements (cheap to keep; reuse across frames).
    // One scratch serves one scan at a time in a command stream (scans recorded one after the
    // other, with the usual barriers between them, may share it).
    class Scratch {
    public:
        Scratch(const Context& context, uint32_t max_count);
        // The device_bytes() a scratch for max_count elements will hold (for memory budgets).
        static uint64_t bytes_for(const Context& context, uint32_t max_count);
        uint32_t capacity() const { return capacity_; }
        const Buffer& buffer() const { return buffer_; }
        uint64_t device_bytes() const { return buffer_.size(); }
        // Layout of buffer(), in uints: [0..2] VkDispatchIndirectCommand, [3] count (clamped to
        // capacity), [4] number of blocks, [16..] one look-back word per block.
        static constexpr uint32_t lookback_offset = shader::sort::SCAN_LOOKBACK;

    private:
        uint32_t capacity_ = 0;
        Buffer buffer_;
    };

    // Records the setup of a scan of `count` uint32 values, where count is read by the GPU from the
    // uint at count_address (values above the scratch capacity are clamped to it). The count must
    // be written and made visible before (a barrier after its producer); record() follows after a
    // barrier, and nothing else may use the scratch in between.
    void record_setup(CommandStream& stream, VkDeviceAddress count_address, Scratch& scratch) const;

    // Records the exclusive prefix sum set up by record_setup. input and output are device
    // addresses of distinct uint arrays (throws std::invalid_argument if they are the same). If total_address != 0 the sum of
    // all values is written there. If gather != 0 (uint indices) the scanned sequence is
    // input[gather[i]] instead of input[i]. The caller records a barrier before (for its inputs and
    // the setup); this ends with its writes NOT yet made visible (caller records barrier()).
    void record(CommandStream& stream, VkDeviceAddress input, VkDeviceAddress output, VkDeviceAddress total_address,
                Scratch& scratch, VkDeviceAddress gather = 0) const;

private:
    std::unique_ptr<Kernel<shader::sort::ScanSetupKernel>> setup_;
    std::unique_ptr<Kernel<shader::sort::ScanLookbackKernel>> scan_;
};

}  // namespace vksplat::gpu
