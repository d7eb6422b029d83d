// The validation layer is wired up: a call that breaks a Vulkan rule reaches the context's message
// list, which is what fails a GPU test (tests/support/gpu_fixture.cpp) when it happens in one.
#include <gtest/gtest.h>

#include "gpu/context_impl.hpp"
#include "support/gpu_fixture.hpp"

namespace vksplat::test {
namespace {

TEST(Validation, AnInvalidCallBecomesAMessage) {
    if (!gpu::validation_layer_installed()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed";
    gpu::ContextOptions options = test_context_options();
    options.validation = true;
    const gpu::Context context(options);  // its own, so the message does not fail other tests
    ASSERT_TRUE(context.validation_messages().empty());

    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 0;  // VUID-VkBufferCreateInfo-size-00912: size must be greater than 0
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    gpu::vk(context).vkCreateBuffer(context.device(), &info, nullptr, &buffer);
    if (buffer) gpu::vk(context).vkDestroyBuffer(context.device(), buffer, nullptr);

    const auto messages = context.validation_messages();
    ASSERT_FALSE(messages.empty());
    EXPECT_NE(messages[0].find("00912"), std::string::npos) << messages[0];
}

}  // namespace
}  // namespace vksplat::test
