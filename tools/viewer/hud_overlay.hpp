#pragma once
// HudOverlay: lines of text in a dark box at the top-left of the window, drawn by OpenCV
// (cv::putText's built-in Hershey font: no font files) into a host-visible buffer and copied over
// the rendered picture. The splat renderer has no text of its own; a copy into the swapchain image
// after it is all the overlay needs.
#include <string>
#include <vector>

#include "glfw_window.hpp"

namespace vksplat::viewer {

class HudOverlay {
public:
    explicit HudOverlay(const GlfwWindow& window);
    ~HudOverlay();
    HudOverlay(const HudOverlay&) = delete;
    HudOverlay& operator=(const HudOverlay&) = delete;

    // Draws `lines`, light grey on dark grey (the same bytes in RGBA and BGRA images), in a box at
    // most max_width x max_height; an empty list draws nothing. Call it before recording, while no
    // frame reads the buffer.
    void set_text(const std::vector<std::string>& lines, uint32_t max_width, uint32_t max_height);
    // Copies the box into `image` (in TRANSFER_DST_OPTIMAL, after the render's copy) and moves the
    // image to PRESENT_SRC.
    void record(VkCommandBuffer commands, VkImage image) const;

private:
    void ensure(VkDeviceSize bytes);

    const GlfwWindow& window_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    void* mapped_ = nullptr;
    VkDeviceSize capacity_ = 0;
    uint32_t width_ = 0, height_ = 0;  // of the box; 0: nothing to draw
};

}  // namespace vksplat::viewer
