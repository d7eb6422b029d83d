#include "hud_overlay.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/imgproc.hpp>

#include "vk_result_check.hpp"
#include "vksplat/error.hpp"

namespace vksplat::viewer {
namespace {

constexpr double kFontScale = 0.4;
constexpr int kLineHeight = 14, kMargin = 4;

}  // namespace

HudOverlay::HudOverlay(const GlfwWindow& window) : window_(window) {}

HudOverlay::~HudOverlay() {
    const VkDevice device = window_.device();
    vkDestroyBuffer(device, buffer_, nullptr);
    vkFreeMemory(device, memory_, nullptr);  // unmaps too
}

void HudOverlay::ensure(VkDeviceSize bytes) {
    if (bytes <= capacity_) return;
    const VkDevice device = window_.device();
    vkDestroyBuffer(device, buffer_, nullptr);
    vkFreeMemory(device, memory_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    capacity_ = 0;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    check(vkCreateBuffer(device, &info, nullptr, &buffer_), "vkCreateBuffer (HUD)");
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device, buffer_, &needs);
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(window_.physical_device(), &properties);
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = properties.memoryTypeCount;
    for (uint32_t t = 0; t < properties.memoryTypeCount; ++t)
        if ((needs.memoryTypeBits & (1u << t)) && (properties.memoryTypes[t].propertyFlags & wanted) == wanted) {
            type = t;
            break;
        }
    if (type == properties.memoryTypeCount) throw GpuError("no host-visible memory for the HUD");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = needs.size;
    alloc.memoryTypeIndex = type;
    check(vkAllocateMemory(device, &alloc, nullptr, &memory_), "vkAllocateMemory (HUD)");
    check(vkBindBufferMemory(device, buffer_, memory_, 0), "vkBindBufferMemory (HUD)");
    check(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory (HUD)");
    capacity_ = bytes;
}

void HudOverlay::set_text(const std::vector<std::string>& lines, uint32_t max_width, uint32_t max_height) {
    width_ = height_ = 0;
    if (lines.empty()) return;
    int widest = 0;
    for (const auto& line : lines) {
        int baseline = 0;
        widest = std::max(widest, cv::getTextSize(line, cv::FONT_HERSHEY_SIMPLEX, kFontScale, 1, &baseline).width);
    }
    width_ = std::min<uint32_t>(max_width, uint32_t(widest + 2 * kMargin));
    height_ = std::min<uint32_t>(max_height, uint32_t(int(lines.size()) * kLineHeight + 2 * kMargin));
    if (width_ == 0 || height_ == 0) {
        width_ = height_ = 0;
        return;
    }
    cv::Mat box(int(height_), int(width_), CV_8UC4, cv::Scalar(24, 24, 24, 255));
    for (size_t i = 0; i < lines.size(); ++i)
        cv::putText(box, lines[i], cv::Point(kMargin, kMargin + int(i + 1) * kLineHeight - 3), cv::FONT_HERSHEY_SIMPLEX,
                    kFontScale, cv::Scalar(235, 235, 235, 255), 1, cv::LINE_AA);
    ensure(VkDeviceSize(width_) * height_ * 4);
    std::memcpy(mapped_, box.data, size_t(width_) * height_ * 4);
}

void HudOverlay::record(VkCommandBuffer commands, VkImage image) const {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    barrier.oldLayout = barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    if (width_ > 0) {
        // After the render's copy into the image (the two copies overlap at the box).
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &barrier);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width_, height_, 1};
        vkCmdCopyBufferToImage(commands, buffer_, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    }
    barrier.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = 0;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr,
                         0, nullptr, 1, &barrier);
}

}  // namespace vksplat::viewer
