#pragma once
// One Vulkan context for a whole test suite: creating a device per test would dominate the run
// time on lavapipe. VKSPLAT_TEST_DEVICE picks the device, VKSPLAT_VALIDATION=1 turns on the
// validation layers (and then every test fails on any validation message).
#include <gtest/gtest.h>

#include <memory>

#include "vksplat/gpu/context.hpp"

namespace vksplat::test {

class GpuTest : public ::testing::Test {
protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite();
    void TearDown() override;
    static gpu::Context& context();

private:
    static std::unique_ptr<gpu::Context> context_;
    static size_t messages_seen_;
};

}  // namespace vksplat::test
