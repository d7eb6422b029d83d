#pragma once
// The window and the Vulkan objects that present into it: GLFW, an instance with the surface
// extensions GLFW asks for, the surface, and a device with a queue that computes and presents.
// All owned here (RAII); vksplat borrows them through gpu::AdoptedDevice.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <string>

#include "vksplat/gpu/context.hpp"

namespace vksplat::viewer {

class GlfwWindow {
public:
    GlfwWindow(int width, int height, const std::string& title, bool validation);
    ~GlfwWindow();
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    GLFWwindow* window() const { return window_; }
    VkInstance instance() const { return instance_; }
    VkSurfaceKHR surface() const { return surface_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return family_; }
    gpu::AdoptedDevice lend() const;

private:
    void release();

    GLFWwindow* window_ = nullptr;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
};

}  // namespace vksplat::viewer
