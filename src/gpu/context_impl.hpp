#pragma once
// What the rest of the library sees of a Context: the device's function table and its limits.
#include <volk.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "vksplat/gpu/context.hpp"

namespace vksplat::gpu {

struct Context::Impl {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    bool owned = true;  // false: instance and device are the application's (AdoptedDevice)
    DeviceInfo info;
    uint64_t memory_budget = 0;  // ContextOptions::memory_budget (0: info.device_local_budget)
    VkPhysicalDeviceMemoryProperties memory{};
    VolkDeviceTable vk{};
    mutable std::mutex messages_mutex;
    std::vector<std::string> validation_messages;
    bool capture_statistics = false;  // pipelines are created with their statistics captured
    mutable std::mutex statistics_mutex;
    std::vector<PipelineStatistics> statistics;
    // Context::held_device_bytes / peak_device_bytes, kept by Buffer (threads may allocate at once).
    mutable std::atomic<uint64_t> held_device_bytes{0}, peak_device_bytes{0};
    void device_bytes_allocated(uint64_t bytes) const;
    void device_bytes_freed(uint64_t bytes) const { held_device_bytes.fetch_sub(bytes); }
};

inline const VolkDeviceTable& vk(const Context& context) { return context.impl().vk; }

}  // namespace vksplat::gpu
