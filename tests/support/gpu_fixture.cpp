#include "support/gpu_fixture.hpp"

#include <cstdlib>
#include <string>

namespace vksplat::test {

std::unique_ptr<gpu::Context> GpuTest::context_;
size_t GpuTest::messages_seen_ = 0;

void GpuTest::SetUpTestSuite() {
    if (context_) return;
    gpu::ContextOptions options;
    if (const char* device = std::getenv("VKSPLAT_TEST_DEVICE")) options.device = device;
    if (const char* validation = std::getenv("VKSPLAT_VALIDATION")) options.validation = std::string(validation) == "1";
    context_ = std::make_unique<gpu::Context>(options);
}

void GpuTest::TearDownTestSuite() {
    context_.reset();
    messages_seen_ = 0;
}

void GpuTest::TearDown() {
    const auto messages = context_->validation_messages();
    for (size_t i = messages_seen_; i < messages.size(); ++i) ADD_FAILURE() << "Vulkan validation: " << messages[i];
    messages_seen_ = messages.size();
}

gpu::Context& GpuTest::context() { return *context_; }

}  // namespace vksplat::test
