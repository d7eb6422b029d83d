#pragma once
// Turns a failed Vulkan call into a GpuError that says which call failed and why; an
// out-of-memory result says so in words, since that is the one a user can act on.
#include <volk.h>

#include <string>

#include "vksplat/error.hpp"
#include "vksplat/gpu/context.hpp"

namespace vksplat::gpu {

// What every out-of-memory message suggests: a smaller budget makes the renderer split frames.
inline constexpr const char* kMemoryBudgetHint =
    "set a smaller memory budget (--memory-budget MB, or ContextOptions::memory_budget) so frames render in "
    "depth-ordered chunks, or use a smaller scene or resolution";

const char* result_name(VkResult result);
[[noreturn]] void throw_vk_error(VkResult result, const char* call);
// The message for an allocation of `bytes` for `what` that failed with an out-of-memory result.
std::string out_of_memory_message(VkResult result, const std::string& what, uint64_t bytes, const DeviceInfo& device);

inline void check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw_vk_error(result, call);
}

}  // namespace vksplat::gpu

#define VKSPLAT_VK(call) ::vksplat::gpu::check((call), #call)
