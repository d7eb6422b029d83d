#include "render/target_copy.hpp"

#include "gpu/context_impl.hpp"

namespace vksplat {

uint32_t render_target_pixel_bytes(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        case VK_FORMAT_R8G8B8A8_UNORM:
        case VK_FORMAT_R8G8B8A8_SRGB:
        case VK_FORMAT_B8G8R8A8_UNORM:
        case VK_FORMAT_B8G8R8A8_SRGB: return 4;
        default: return 0;
    }
}

namespace render {
namespace {

VkImageMemoryBarrier image_barrier(VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src_access,
                                   VkAccessFlags dst_access) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    return barrier;
}

}  // namespace

void record_target_copy(gpu::CommandStream& stream, const gpu::Buffer& source, const RenderTarget& target,
                        uint32_t width, uint32_t height) {
    const auto& vk = gpu::vk(stream.context());
    const VkCommandBuffer cb = stream.handle();
    const VkAccessFlags any_access = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    if (target.image) {
        const auto into = image_barrier(target.image, target.old_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                        any_access, VK_ACCESS_TRANSFER_WRITE_BIT);
        vk.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                                nullptr, 1, &into);
        VkBufferImageCopy region{};
        region.bufferRowLength = width;
        region.bufferImageHeight = height;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {width, height, 1};
        vk.vkCmdCopyBufferToImage(cb, source.handle(), target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        const auto out = image_barrier(target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, target.final_layout,
                                       VK_ACCESS_TRANSFER_WRITE_BIT, any_access);
        vk.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                                nullptr, 1, &out);
        return;
    }
    const VkDeviceSize bytes = VkDeviceSize(width) * height * render_target_pixel_bytes(target.format);
    const VkBufferCopy region{0, target.offset, bytes};
    vk.vkCmdCopyBuffer(cb, source.handle(), target.buffer, 1, &region);
    VkBufferMemoryBarrier out{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    out.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    out.dstAccessMask = any_access;
    out.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    out.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    out.buffer = target.buffer;
    out.offset = target.offset;
    out.size = bytes;
    vk.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 1,
                            &out, 0, nullptr);
}

}  // namespace render
}  // namespace vksplat
