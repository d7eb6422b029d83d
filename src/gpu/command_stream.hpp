#pragma once
// CommandStream: records compute work into one command buffer, submits it and waits (at once, or
// later: the host can prepare other work while it runs).
// It also owns a timestamp query pool, so every recorded stage can be timed on the GPU.
// Built on an application's command buffer instead, it only records into it (no begin, submit,
// or timestamps): the application owns that buffer's life and its submission.
#include <volk.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/compute_pipeline.hpp"
#include "gpu/kernel.hpp"

namespace vksplat::gpu {

struct StageTime {
    std::string label;
    double milliseconds = 0;
};

class CommandStream {
public:
    explicit CommandStream(const Context& context, uint32_t max_timestamps = 64);
    // Records into an application's command buffer, which it has begun and will end and submit.
    struct Recording {
        VkCommandBuffer command_buffer;
    };
    CommandStream(const Context& context, Recording recording);
    ~CommandStream();
    CommandStream(const CommandStream&) = delete;
    CommandStream& operator=(const CommandStream&) = delete;

    void begin();
    // Records `kernel` over groups_x x groups_y workgroups with its push constants: only its own
    // push type is accepted (gpu/kernel.hpp).
    template <class P>
    void dispatch(const PushKernel<P>& kernel, const std::type_identity_t<P>& push, uint32_t groups_x,
                  uint32_t groups_y = 1) {
        dispatch(static_cast<const ComputePipeline&>(kernel), &push, sizeof(push), groups_x, groups_y);
    }
    // Group counts come from a VkDispatchIndirectCommand the GPU wrote at `offset` of `args`.
    template <class P>
    void dispatch_indirect(const PushKernel<P>& kernel, const std::type_identity_t<P>& push, const Buffer& args,
                           VkDeviceSize offset) {
        dispatch_indirect(static_cast<const ComputePipeline&>(kernel), &push, sizeof(push), args, offset);
    }
    // Makes every earlier shader or transfer write visible to every later shader, indirect-argument
    // or transfer access. Passes are ordered by this one coarse barrier: they are few and each
    // touches most of its inputs, so finer barriers would buy nothing measurable.
    void barrier();
    // Orders everything submitted earlier on the queue (any stage, any write) before the compute and
    // transfer work recorded next: the first thing recorded into an application's command buffer.
    void barrier_after_everything();
    // Makes earlier transfer writes visible to the host (for mapped readback buffers read later).
    void barrier_before_host_read();
    void fill(const Buffer& buffer, uint32_t value, VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE);
    // Writes up to 64 KiB of host data into a device buffer from inside the command buffer
    // (vkCmdUpdateBuffer): per-frame parameters need no staging buffer this way.
    void update(const Buffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    void copy(const Buffer& source, const Buffer& destination, VkDeviceSize bytes, VkDeviceSize source_offset = 0,
              VkDeviceSize destination_offset = 0);
    // Marks the end of a stage: the time from the previous mark (or begin()) is reported under label.
    void mark(const std::string& label);
    void submit_and_wait();
    // submit_and_wait() in two halves; a stream is not begun again before its wait().
    void submit();
    void wait();
    // Stage times of the last submission (empty if the queue has no timestamps).
    std::vector<StageTime> stage_times() const;

    VkCommandBuffer handle() const { return command_buffer_; }
    const Context& context() const { return context_; }

private:
    void dispatch(const ComputePipeline& pipeline, const void* push, uint32_t push_bytes, uint32_t groups_x,
                  uint32_t groups_y);
    void dispatch_indirect(const ComputePipeline& pipeline, const void* push, uint32_t push_bytes,
                           const Buffer& args, VkDeviceSize offset);

    const Context& context_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    uint32_t max_timestamps_ = 0;
    std::vector<std::string> labels_;
    std::vector<StageTime> times_;
};

}  // namespace vksplat::gpu
