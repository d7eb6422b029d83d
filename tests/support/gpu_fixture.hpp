#pragma once
// One Vulkan context for a whole test binary: creating a device per test would dominate the run
// time on lavapipe. VKSPLAT_TEST_DEVICE picks the device. The validation layer
// (VK_LAYER_KHRONOS_validation, with synchronisation validation) is on whenever it is installed;
// VKSPLAT_VALIDATION=0 turns it off. While it is on, a test fails if any validation error or
// warning arrives during it, whether it uses GpuTest or shared_test_context().
#include <gtest/gtest.h>

#include "vksplat/gpu/context.hpp"

namespace vksplat::test {

// The options every test context is made with (device and validation from the environment, as
// above). Says once on stderr when validation is wanted but the layer is not installed.
gpu::ContextOptions test_context_options();

// The test binary's one context, created on first use.
gpu::Context& shared_test_context();

class GpuTest : public ::testing::Test {
protected:
    static gpu::Context& context() { return shared_test_context(); }
};

}  // namespace vksplat::test
