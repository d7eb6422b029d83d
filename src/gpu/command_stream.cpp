#include "gpu/command_stream.hpp"

#include "gpu/context_impl.hpp"
#include "gpu/vk_check.hpp"

namespace vksplat::gpu {

CommandStream::CommandStream(const Context& context, uint32_t max_timestamps)
    : context_(context), max_timestamps_(max_timestamps) {
    const auto& d = context.impl();
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = d.queue_family;
    VKSPLAT_VK(d.vk.vkCreateCommandPool(d.device, &pool_info, nullptr, &pool_));

    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VKSPLAT_VK(d.vk.vkAllocateCommandBuffers(d.device, &alloc, &command_buffer_));

    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VKSPLAT_VK(d.vk.vkCreateFence(d.device, &fence_info, nullptr, &fence_));

    if (d.info.timestamp_period_ns > 0 && max_timestamps > 0) {
        VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        query_info.queryCount = max_timestamps + 1;
        VKSPLAT_VK(d.vk.vkCreateQueryPool(d.device, &query_info, nullptr, &queries_));
    }
}

CommandStream::CommandStream(const Context& context, Recording recording)
    : context_(context), command_buffer_(recording.command_buffer) {}

CommandStream::~CommandStream() {
    if (!pool_) return;  // recorded into an application's command buffer: nothing of ours to free
    const auto& d = context_.impl();
    if (queries_) d.vk.vkDestroyQueryPool(d.device, queries_, nullptr);
    d.vk.vkDestroyFence(d.device, fence_, nullptr);
    d.vk.vkDestroyCommandPool(d.device, pool_, nullptr);
}

void CommandStream::begin() {
    const auto& d = context_.impl();
    VKSPLAT_VK(d.vk.vkResetCommandBuffer(command_buffer_, 0));
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VKSPLAT_VK(d.vk.vkBeginCommandBuffer(command_buffer_, &info));
    labels_.clear();
    times_.clear();
    if (queries_) {
        d.vk.vkCmdResetQueryPool(command_buffer_, queries_, 0, max_timestamps_ + 1);
        d.vk.vkCmdWriteTimestamp(command_buffer_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    }
}

void CommandStream::dispatch(const ComputePipeline& pipeline, const void* push, uint32_t push_bytes,
                             uint32_t groups_x, uint32_t groups_y) {
    if (groups_x == 0 || groups_y == 0) return;
    const auto& d = context_.impl();
    d.vk.vkCmdBindPipeline(command_buffer_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    if (push_bytes) d.vk.vkCmdPushConstants(command_buffer_, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push);
    d.vk.vkCmdDispatch(command_buffer_, groups_x, groups_y, 1);
}

void CommandStream::dispatch_indirect(const ComputePipeline& pipeline, const void* push, uint32_t push_bytes,
                                      const Buffer& args, VkDeviceSize offset) {
    const auto& d = context_.impl();
    d.vk.vkCmdBindPipeline(command_buffer_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    if (push_bytes) d.vk.vkCmdPushConstants(command_buffer_, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes, push);
    d.vk.vkCmdDispatchIndirect(command_buffer_, args.handle(), offset);
}

void CommandStream::barrier() {
    VkMemoryBarrier memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    memory.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    memory.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                           VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    context_.impl().vk.vkCmdPipelineBarrier(
        command_buffer_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
        &memory, 0, nullptr, 0, nullptr);
}

void CommandStream::barrier_after_everything() {
    VkMemoryBarrier memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    memory.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    memory.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                           VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    context_.impl().vk.vkCmdPipelineBarrier(
        command_buffer_, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
        &memory, 0, nullptr, 0, nullptr);
}

void CommandStream::barrier_before_host_read() {
    VkMemoryBarrier memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    memory.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    memory.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    context_.impl().vk.vkCmdPipelineBarrier(command_buffer_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                                            0, 1, &memory, 0, nullptr, 0, nullptr);
}

void CommandStream::fill(const Buffer& buffer, uint32_t value, VkDeviceSize offset, VkDeviceSize size) {
    context_.impl().vk.vkCmdFillBuffer(command_buffer_, buffer.handle(), offset, size, value);
}

void CommandStream::update(const Buffer& buffer, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
    context_.impl().vk.vkCmdUpdateBuffer(command_buffer_, buffer.handle(), offset, bytes, data);
}

void CommandStream::copy(const Buffer& source, const Buffer& destination, VkDeviceSize bytes,
                         VkDeviceSize source_offset, VkDeviceSize destination_offset) {
    if (bytes == 0) return;
    VkBufferCopy region{source_offset, destination_offset, bytes};
    context_.impl().vk.vkCmdCopyBuffer(command_buffer_, source.handle(), destination.handle(), 1, &region);
}

void CommandStream::mark(const std::string& label) {
    if (!queries_ || labels_.size() >= max_timestamps_) return;
    labels_.push_back(label);
    context_.impl().vk.vkCmdWriteTimestamp(command_buffer_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_,
                                           static_cast<uint32_t>(labels_.size()));
}

void CommandStream::submit_and_wait() {
    submit();
    wait();
}

void CommandStream::submit() {
    const auto& d = context_.impl();
    VKSPLAT_VK(d.vk.vkEndCommandBuffer(command_buffer_));
    VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    info.commandBufferCount = 1;
    info.pCommandBuffers = &command_buffer_;
    VKSPLAT_VK(d.vk.vkResetFences(d.device, 1, &fence_));
    VKSPLAT_VK(d.vk.vkQueueSubmit(d.queue, 1, &info, fence_));
}

void CommandStream::wait() {
    const auto& d = context_.impl();
    VKSPLAT_VK(d.vk.vkWaitForFences(d.device, 1, &fence_, VK_TRUE, UINT64_MAX));

    times_.clear();
    if (!queries_ || labels_.empty()) return;
    std::vector<uint64_t> stamps(labels_.size() + 1);
    VKSPLAT_VK(d.vk.vkGetQueryPoolResults(d.device, queries_, 0, static_cast<uint32_t>(stamps.size()),
                                          stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double period_ms = d.info.timestamp_period_ns * 1e-6;
    for (size_t i = 0; i < labels_.size(); ++i)
        times_.push_back({labels_[i], static_cast<double>(stamps[i + 1] - stamps[i]) * period_ms});
}

std::vector<StageTime> CommandStream::stage_times() const { return times_; }

}  // namespace vksplat::gpu
