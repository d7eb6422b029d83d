#pragma once
// The viewer's Vulkan calls (through the system loader, not the library's volk) turn a failure
// into a GpuError naming the call.
#include <vulkan/vulkan.h>

#include <string>

#include "vksplat/error.hpp"

namespace vksplat::viewer {

inline void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw GpuError(std::string(what) + " failed (VkResult " + std::to_string(result) + ")");
}

}  // namespace vksplat::viewer
