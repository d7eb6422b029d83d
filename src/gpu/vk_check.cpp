#include "gpu/vk_check.hpp"

namespace vksplat::gpu {

const char* result_name(VkResult result) {
    switch (result) {
        case VK_SUCCESS: return "VK_SUCCESS";
        case VK_NOT_READY: return "VK_NOT_READY";
        case VK_TIMEOUT: return "VK_TIMEOUT";
        case VK_INCOMPLETE: return "VK_INCOMPLETE";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
        case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
        case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
        case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
        case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
        case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
        case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
        case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
        default: return "unknown VkResult";
    }
}

void throw_vk_error(VkResult result, const char* call) {
    std::string message = std::string("Vulkan call failed: ") + call + " returned " + result_name(result) +
                          " (" + std::to_string(static_cast<int>(result)) + ")";
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        message += std::string(": the GPU ran out of memory; ") + kMemoryBudgetHint;
    throw GpuError(message);
}

std::string out_of_memory_message(VkResult result, const std::string& what, uint64_t bytes, const DeviceInfo& device) {
    const auto mebibytes = [](uint64_t b) { return std::to_string((b + (1 << 20) - 1) >> 20) + " MiB"; };
    return std::string(result == VK_ERROR_OUT_OF_HOST_MEMORY ? "out of host memory" : "out of GPU memory") +
           " allocating " + std::to_string(bytes) + " bytes (" + mebibytes(bytes) + ") for '" + what + "' on " +
           device.name + " (" + mebibytes(device.device_local_bytes) + " device-local): " + result_name(result) +
           "; " + kMemoryBudgetHint;
}

}  // namespace vksplat::gpu
