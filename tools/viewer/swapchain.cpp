#include "swapchain.hpp"

#include <algorithm>

#include "vk_result_check.hpp"
#include "vksplat/error.hpp"
#include "vksplat/render/render_target.hpp"

namespace vksplat::viewer {
namespace {

// An 8-bit format vksplat writes; UNORM first, although _SRGB gets the same bytes (the colours are
// display-encoded already, see render/render_target.hpp).
VkSurfaceFormatKHR choose_format(const std::vector<VkSurfaceFormatKHR>& available) {
    for (const VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                                  VK_FORMAT_R8G8B8A8_SRGB})
        for (const auto& f : available)
            if (f.format == wanted) return f;
    throw GpuError("the window offers no 8-bit RGBA or BGRA swapchain format");
}

}  // namespace

Swapchain::Swapchain(const GlfwWindow& window, VkExtent2D wanted, VkSwapchainKHR old) : window_(window) {
    const VkPhysicalDevice physical = window.physical_device();
    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, window.surface(), &caps), "surface capabilities");
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw GpuError("the window's swapchain images cannot be transfer destinations");
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, window.surface(), &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, window.surface(), &count, formats.data());
    const VkSurfaceFormatKHR format = choose_format(formats);
    // Mailbox shows the newest frame without tearing and without tying the frame time to the
    // display's refresh; FIFO is always there.
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, window.surface(), &count, nullptr);
    std::vector<VkPresentModeKHR> modes(count);
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, window.surface(), &count, modes.data());
    const bool mailbox = std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end();

    extent_ = caps.currentExtent.width != 0xffffffffu
                  ? caps.currentExtent
                  : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                               std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    uint32_t images = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) images = std::min(images, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = window.surface();
    info.minImageCount = images;
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = mailbox ? VK_PRESENT_MODE_MAILBOX_KHR : VK_PRESENT_MODE_FIFO_KHR;
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    check(vkCreateSwapchainKHR(window.device(), &info, nullptr, &swapchain_), "vkCreateSwapchainKHR");
    format_ = format.format;

    vkGetSwapchainImagesKHR(window.device(), swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(window.device(), swapchain_, &count, images_.data());
    for (uint32_t i = 0; i < count; ++i) {
        VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore semaphore;
        check(vkCreateSemaphore(window.device(), &semaphore_info, nullptr, &semaphore), "vkCreateSemaphore");
        drawn_.push_back(semaphore);
    }
}

Swapchain::~Swapchain() {
    for (VkSemaphore s : drawn_) vkDestroySemaphore(window_.device(), s, nullptr);
    vkDestroySwapchainKHR(window_.device(), swapchain_, nullptr);
}

}  // namespace vksplat::viewer
