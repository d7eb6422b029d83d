#pragma once
// Context: one Vulkan device and a compute queue, owned by vksplat or adopted from the caller.
// Everything GPU-side in vksplat hangs off a Context; there is no process-wide Vulkan state of
// ours (volk's loader entry points are the one exception, and they are the same for everyone).
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vksplat::gpu {

struct DeviceInfo {
    uint32_t index = 0;                 // position in vkEnumeratePhysicalDevices
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;                 // driver name and version info
    uint32_t api_version = 0;
    uint32_t subgroup_size = 0;         // the default size compute shaders run with
    uint32_t min_subgroup_size = 0;     // smallest size the driver may pick (AMD: 32 vs 64)
    uint64_t device_local_bytes = 0;    // largest device-local heap
    float timestamp_period_ns = 0;      // 0 when the queue has no timestamps
    bool int64_atomics = false;         // 64-bit buffer atomics: needed for per-Gaussian statistics
    bool usable = false;                // has what vksplat needs (see unusable_reason)
    std::string unusable_reason;

    std::string type_name() const;
};

struct ContextOptions {
    // "" picks the first usable discrete GPU, then integrated, then anything (lavapipe).
    // A number picks by index; any other text picks the first device whose name contains it.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation (with synchronisation validation) when installed.
    bool validation = false;
};

// Every physical device, with whether vksplat can use it.
std::vector<DeviceInfo> list_devices();

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const;
    VkPhysicalDevice physical_device() const;
    VkDevice device() const;
    VkQueue queue() const;
    uint32_t queue_family() const;
    const DeviceInfo& info() const;
    // Validation messages (errors and warnings) seen so far; empty unless validation is on.
    std::vector<std::string> validation_messages() const;

    struct Impl;
    Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::gpu
