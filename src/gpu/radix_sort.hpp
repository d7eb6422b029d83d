#pragma once
// RadixSort: stable LSD radix sort of (key, value) uint32 pairs on the GPU, by the low key_bits
// bits of the keys, with the count read from GPU memory. Per pass (digits of up to 8 bits) a
// scatter kernel ranks each block's keys with subgroup ballots, reorders the block by digit in
// shared memory and writes it in runs. Where the earlier blocks' digit counts come from depends on
// the size (radix_sort.cpp): small sorts run one sweep (one histogram kernel for all passes, then
// decoupled look-back inside the scatter, with a fallback that needs no forward-progress
// guarantee: 1 + passes kernels), large ones a block histogram and its scan per pass
// (3 x passes kernels). A frame's fixed cost is its chain of dependent kernels, about 4.5 us each
// on an H100 however little they do; large sorts are bound by memory instead.
// Kernels: shaders/sort/radix_*.comp, layouts in shaders/sort/radix_sort.h.
// Works for any subgroup size (sizes come from DeviceInfo as specialisation constants; the
// workgroup size is a multiple of the subgroup size, and subgroups are assumed to be full, as
// every driver we know of runs them for such workgroups).
#include <cstdint>
#include <memory>
#include <optional>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "shaders/sort/radix_sort.h"

namespace vksplat::shader::sort {
struct RadixSetupKernel;
struct RadixHistogramKernel;
struct RadixScatterOneSweepKernel;
struct RadixBlockHistogramKernel;
struct RadixScanHistogramKernel;
struct RadixScatterKernel;
}  // namespace vksplat::shader::sort

namespace vksplat::gpu {

class RadixSort {
public:
    // lookback_spins: polls of a predecessor block that has not published its digit counts before
    // a scatter block counts them itself (0 makes that fallback common: tests use it to check it).
    static constexpr uint32_t default_lookback_spins = 64;
    explicit RadixSort(const Context& context, uint32_t lookback_spins = default_lookback_spins);
    ~RadixSort();
    RadixSort(const RadixSort&) = delete;
    RadixSort& operator=(const RadixSort&) = delete;

    // Ping-pong buffers, look-back words and control for sorts of up to max_count pairs. One
    // scratch serves one sort at a time in a command stream.
    class Scratch {
    public:
        Scratch(const Context& context, uint32_t max_count);
        // The device_bytes() a scratch for max_count pairs will hold (for memory budgets).
        static uint64_t bytes_for(const Context& context, uint32_t max_count);
        uint32_t capacity() const { return capacity_; }
        // Device memory held (for memory statistics).
        uint64_t device_bytes() const {
            return keys_.size() + values_.size() + block_words_.size() + control_.size();
        }

    private:
        friend class RadixSort;
        uint32_t capacity_ = 0;
        Buffer keys_;       // ping-pong partner of the caller's keys
        Buffer values_;     // ... and values
        Buffer block_words_;  // one sweep: look-back words [block][pass][digit]; else hist[digit][block]
        Buffer control_;    // [0..2] DispatchArgs, [3] count, [4] blocks; per-pass digit totals
    };

    // Digit passes of at most 8 bits: keys of up to 32 bits.
    static constexpr uint32_t max_passes = shader::sort::MAX_PASSES;

    // What a kernel that writes a sort's keys needs to stand in for the histogram kernel
    // (shaders/sort/radix_digit_counts.glsl): count the keys' digits into the per-pass totals
    // and empty the look-back words.
    using DigitCounting = shader::sort::DigitCounting;

    // Where the count of pairs is known when recording: records the setup of a sort of
    // min(count, capacity) pairs as buffer writes (no kernel), to be made visible by the caller's
    // barrier before the kernel that writes the keys. When the sort runs one sweep, returns how
    // that kernel counts the keys' digits; then record(..., digits_counted = true) skips the
    // histogram kernel, and every key must be counted exactly once. Otherwise records nothing and
    // returns nothing: the sort is set up by record_setup. Each kernel dropped from a frame's chain
    // saves its launch and latency (a few microseconds).
    std::optional<DigitCounting> record_host_setup(CommandStream& stream, const Buffer& keys, const Buffer& values,
                                                   uint32_t count, uint32_t key_bits, Scratch& scratch) const;

    // Records the setup of a sort of `count` pairs, where count is read by the GPU from
    // count_address (clamped to the capacity of keys, values and scratch). The count must be
    // written and made visible before (a barrier after its producer); record() follows after a
    // barrier, with the same keys, values and scratch, and nothing else may use the scratch in
    // between. Recorded apart so that a frame can run it beside earlier work: each kernel in a
    // chain costs a few microseconds however little it does.
    void record_setup(CommandStream& stream, const Buffer& keys, const Buffer& values, VkDeviceAddress count_address,
                      Scratch& scratch) const;

    // Stable LSD sort of the (key, value) uint32 pairs set up by record_setup or record_host_setup
    // (digits_counted: the keys' producer counted their digits as that returned; same key_bits),
    // by the low key_bits (1..32) bits of the keys. Elements past count are left untouched. The
    // result ends in `keys` and `values` (the number of passes is made even, with the bits spread
    // over them, so the ping-pong ends where it began). The caller records a barrier before (for
    // its inputs and the setup); this records barriers between its own kernels and ends with its
    // writes NOT yet made visible (caller records barrier()).
    void record(CommandStream& stream, const Buffer& keys, const Buffer& values, uint32_t key_bits,
                Scratch& scratch, bool digits_counted = false) const;

    // Digit passes a sort by key_bits (1..32) bits makes: what its time scales with.
    static uint32_t passes_for(uint32_t key_bits);

    // Keys per block of the histogram and scatter kernels on this device.
    uint32_t block_size() const { return block_size_; }
    // ... on a device of these properties (radix_sort.cpp says how they choose it).
    static uint32_t block_size_for(const DeviceInfo& info);

private:
    // The digits of each pass of a sort by key_bits bits (totals left 0).
    static DigitCounting digits_for(uint32_t key_bits);
    // Pairs a sort of these buffers may hold, and whether it runs one sweep.
    static uint64_t capacity(const Buffer& keys, const Buffer& values, const Scratch& scratch);
    bool one_sweep(uint64_t capacity) const;

    uint32_t block_size_ = 0;
    std::unique_ptr<Kernel<shader::sort::RadixSetupKernel>> setup_;
    std::unique_ptr<Kernel<shader::sort::RadixHistogramKernel>> histogram_;  // one sweep: every pass's digit totals
    std::unique_ptr<Kernel<shader::sort::RadixScatterOneSweepKernel>> one_sweep_scatter_;
    std::unique_ptr<Kernel<shader::sort::RadixBlockHistogramKernel>> block_histogram_;  // large sorts, per pass
    std::unique_ptr<Kernel<shader::sort::RadixScanHistogramKernel>> scan_histogram_;
    std::unique_ptr<Kernel<shader::sort::RadixScatterKernel>> scatter_;
};

}  // namespace vksplat::gpu
