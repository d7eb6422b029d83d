#pragma once
// Swapchain: the window's presentable images, in a format vksplat can write (8-bit RGBA or
// BGRA), usable as transfer destinations, since Renderer::record copies the picture into them.
#include "glfw_window.hpp"

#include <vector>

namespace vksplat::viewer {

class Swapchain {
public:
    // `old` (may be null) is retired in favour of the new one, as on a resize.
    Swapchain(const GlfwWindow& window, VkExtent2D wanted, VkSwapchainKHR old);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    const std::vector<VkImage>& images() const { return images_; }
    // Signalled by the frame that draws image i; the presentation of image i waits on it.
    VkSemaphore drawn(uint32_t i) const { return drawn_[i]; }

private:
    const GlfwWindow& window_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkSemaphore> drawn_;
};

}  // namespace vksplat::viewer
