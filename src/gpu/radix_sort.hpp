#pragma once
// RadixSort: stable LSD radix sort of (key, value) uint32 pairs on the GPU, by the low key_bits
// bits of the keys, with the count read from GPU memory. Per pass (digits of up to 8 bits):
// per-block digit histogram (and per-digit totals) -> one-dispatch scan into output positions ->
// stable scatter: keys ranked
// with subgroup ballots, each block reordered by digit in shared memory, then written in runs.
// Works for any subgroup size (sizes come from DeviceInfo as specialisation constants; the
// workgroup size is a multiple of the subgroup size, and subgroups are assumed to be full, as
// every driver we know of runs them for such workgroups).
#include <cstdint>
#include <memory>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/compute_pipeline.hpp"

namespace vksplat::gpu {

class RadixSort {
public:
    explicit RadixSort(const Context& context);
    ~RadixSort();
    RadixSort(const RadixSort&) = delete;
    RadixSort& operator=(const RadixSort&) = delete;

    // Ping-pong buffers, histogram and scan scratch for sorts of up to max_count pairs. One
    // scratch serves one sort at a time in a command stream.
    class Scratch {
    public:
        Scratch(const Context& context, uint32_t max_count);
        // The device_bytes() a scratch for max_count pairs will hold (for memory budgets).
        static uint64_t bytes_for(const Context& context, uint32_t max_count);
        uint32_t capacity() const { return capacity_; }
        // Device memory held (for memory statistics).
        uint64_t device_bytes() const {
            return keys_.size() + values_.size() + histogram_.size() + control_.size();
        }

    private:
        friend class RadixSort;
        uint32_t capacity_ = 0;
        Buffer keys_;       // ping-pong partner of the caller's keys
        Buffer values_;     // ... and values
        Buffer histogram_;  // radix x blocks digit counts, scanned in place
        Buffer control_;    // [0..2] DispatchArgs, [3] count, [4] blocks; per-pass digit totals
    };

    // Stable LSD sort of (key, value) uint32 pairs by the low key_bits (1..32) bits of the keys.
    // count is read by the GPU from count_address (clamped to the capacity of keys, values and
    // scratch). Elements past count are left untouched. The result ends in `keys` and `values`
    // (the number of passes is made even, with the bits spread over them, so the ping-pong ends
    // where it began). The caller records a barrier before (for its inputs); this records
    // barriers between its own kernels and ends with its writes NOT yet made visible (caller
    // records barrier()).
    void record(CommandStream& stream, const Buffer& keys, const Buffer& values, VkDeviceAddress count_address,
                uint32_t key_bits, Scratch& scratch) const;

    // Digit passes a sort by key_bits (1..32) bits makes: what its time scales with.
    static uint32_t passes_for(uint32_t key_bits);

    // Keys per block of the histogram and scatter kernels on this device.
    uint32_t block_size() const { return block_size_; }

private:
    std::unique_ptr<ComputePipeline> scan_histogram_;
    uint32_t block_size_ = 0;
    std::unique_ptr<ComputePipeline> setup_;
    std::unique_ptr<ComputePipeline> histogram_;
    std::unique_ptr<ComputePipeline> scatter_;
};

}  // namespace vksplat::gpu
