// Out-of-memory results become a GpuError that says what ran out and suggests a memory budget.
#include <gtest/gtest.h>

#include <string>

#include "gpu/vk_check.hpp"

namespace vksplat::gpu {
namespace {

std::string message_of(VkResult result) {
    try {
        throw_vk_error(result, "vkAllocateMemory");
    } catch (const GpuError& e) {
        return e.what();
    }
    return {};
}

TEST(OutOfMemory, DeviceAndHostResultsSuggestAMemoryBudget) {
    for (const VkResult result : {VK_ERROR_OUT_OF_DEVICE_MEMORY, VK_ERROR_OUT_OF_HOST_MEMORY}) {
        const std::string message = message_of(result);
        EXPECT_NE(message.find("vkAllocateMemory"), std::string::npos) << message;
        EXPECT_NE(message.find(result_name(result)), std::string::npos) << message;
        EXPECT_NE(message.find("ran out of memory"), std::string::npos) << message;
        EXPECT_NE(message.find("--memory-budget"), std::string::npos) << message;
    }
    EXPECT_EQ(message_of(VK_ERROR_DEVICE_LOST).find("--memory-budget"), std::string::npos);
}

TEST(OutOfMemory, AFailedAllocationSaysWhatHowLargeAndSuggestsABudget) {
    DeviceInfo device;
    device.name = "Test GPU";
    device.device_local_bytes = 8ull << 30;
    const std::string message = out_of_memory_message(VK_ERROR_OUT_OF_DEVICE_MEMORY, "tile keys", 3u << 20, device);
    EXPECT_NE(message.find("out of GPU memory"), std::string::npos) << message;
    EXPECT_NE(message.find("'tile keys'"), std::string::npos) << message;
    EXPECT_NE(message.find("3145728 bytes (3 MiB)"), std::string::npos) << message;
    EXPECT_NE(message.find("Test GPU (8192 MiB device-local)"), std::string::npos) << message;
    EXPECT_NE(message.find("--memory-budget"), std::string::npos) << message;
    EXPECT_NE(out_of_memory_message(VK_ERROR_OUT_OF_HOST_MEMORY, "x", 1, device).find("out of host memory"),
              std::string::npos);
}

}  // namespace
}  // namespace vksplat::gpu
