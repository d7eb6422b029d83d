#include "glfw_window.hpp"

#include <vector>

#include "vk_result_check.hpp"
#include "vksplat/error.hpp"

namespace vksplat::viewer {
namespace {

int type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        default: return 2;
    }
}

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, bool validation) {
    if (!glfwInit()) {
        const char* message = nullptr;
        glfwGetError(&message);
        throw GpuError(std::string("cannot open a window: ") + (message ? message : "GLFW failed to initialise") +
                       " (is DISPLAY set?)");
    }
    try {
        if (!glfwVulkanSupported()) throw GpuError("GLFW finds no Vulkan loader that can present to this display");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window_) throw GpuError("cannot create a " + std::to_string(width) + "x" + std::to_string(height) + " window");

        uint32_t glfw_count = 0;
        const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&glfw_count);
        const std::vector<const char*> extensions(glfw_extensions, glfw_extensions + glfw_count);
        const char* layer = "VK_LAYER_KHRONOS_validation";
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "vksplat view";
        app.apiVersion = VK_API_VERSION_1_2;
        VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        instance_info.pApplicationInfo = &app;
        instance_info.enabledExtensionCount = glfw_count;
        instance_info.ppEnabledExtensionNames = extensions.data();
        instance_info.enabledLayerCount = validation ? 1 : 0;
        instance_info.ppEnabledLayerNames = &layer;
        check(vkCreateInstance(&instance_info, nullptr, &instance_), "vkCreateInstance");
        check(glfwCreateWindowSurface(instance_, window_, nullptr, &surface_), "glfwCreateWindowSurface");

        // The best ranked device with one queue family that computes and presents to the window.
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance_, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance_, &count, devices.data());
        int best_rank = 1 << 30;
        for (VkPhysicalDevice candidate : devices) {
            VkPhysicalDeviceProperties properties;
            vkGetPhysicalDeviceProperties(candidate, &properties);
            if (properties.apiVersion < VK_API_VERSION_1_2 || type_rank(properties.deviceType) >= best_rank) continue;
            uint32_t families = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
            std::vector<VkQueueFamilyProperties> family_properties(families);
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, family_properties.data());
            for (uint32_t f = 0; f < families; ++f) {
                VkBool32 presents = VK_FALSE;
                vkGetPhysicalDeviceSurfaceSupportKHR(candidate, f, surface_, &presents);
                if ((family_properties[f].queueFlags & VK_QUEUE_COMPUTE_BIT) && presents) {
                    physical_ = candidate;
                    family_ = f;
                    best_rank = type_rank(properties.deviceType);
                    break;
                }
            }
        }
        if (!physical_) throw GpuError("no Vulkan 1.2 device has a queue that both computes and presents to the window");

        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.bufferDeviceAddress = VK_TRUE;  // what vksplat needs (gpu/context.hpp)
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = family_;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        device_info.pNext = &features12;
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        device_info.enabledExtensionCount = 1;
        device_info.ppEnabledExtensionNames = &swapchain_extension;
        check(vkCreateDevice(physical_, &device_info, nullptr, &device_), "vkCreateDevice");
        vkGetDeviceQueue(device_, family_, 0, &queue_);
    } catch (...) {
        release();  // a constructor that throws gets no destructor call
        throw;
    }
}

GlfwWindow::~GlfwWindow() { release(); }

void GlfwWindow::release() {
    if (device_) vkDestroyDevice(device_, nullptr);
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
    if (window_) glfwDestroyWindow(window_);
    device_ = VK_NULL_HANDLE;
    surface_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
    window_ = nullptr;
    glfwTerminate();
}

gpu::AdoptedDevice GlfwWindow::lend() const {
    gpu::AdoptedDevice lent;
    lent.instance = instance_;
    lent.physical_device = physical_;
    lent.device = device_;
    lent.queue_family = family_;
    lent.queue = queue_;
    lent.get_instance_proc_addr = vkGetInstanceProcAddr;
    return lent;
}

}  // namespace vksplat::viewer
