#pragma once
// PrefixScan: exclusive prefix sum of uint32 values on the GPU, with the element count read from
// GPU memory (no CPU round trip): a one-invocation setup kernel turns the count into indirect
// dispatch sizes, then reduce per block -> scan of the block sums (one workgroup, any number of
// them) -> downsweep per block. Works for any subgroup size.
#include <cstdint>
#include <memory>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "gpu/compute_pipeline.hpp"

namespace vksplat::gpu {

class PrefixScan {
public:
    static constexpr uint32_t workgroup_size = 128;
    static constexpr uint32_t items_per_thread = 16;
    static constexpr uint32_t block_size = workgroup_size * items_per_thread;  // elements per block

    explicit PrefixScan(const Context& context);
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
        // capacity), [4] number of blocks, [16..] one sum per block.
        static constexpr uint32_t sums_offset = 16;

    private:
        uint32_t capacity_ = 0;
        Buffer buffer_;
    };

    // Records an exclusive prefix sum of `count` uint32 values, where count is read by the GPU from
    // the uint at count_address (values above the scratch capacity are clamped to it). input and
    // output are device addresses of uint arrays and may be the same (in place). If
    // total_address != 0 the sum of all values is written there. No CPU round trip: dispatch
    // sizes are computed on the GPU. The caller records a barrier before (for its inputs); this
    // records barriers between its own kernels and ends with its writes NOT yet made visible
    // (caller records barrier()).
    void record(CommandStream& stream, VkDeviceAddress input, VkDeviceAddress output, VkDeviceAddress count_address,
                VkDeviceAddress total_address, Scratch& scratch) const;

private:
    std::unique_ptr<ComputePipeline> setup_;
    std::unique_ptr<ComputePipeline> reduce_;
    std::unique_ptr<ComputePipeline> blocks_;
    std::unique_ptr<ComputePipeline> downsweep_;
};

}  // namespace vksplat::gpu
