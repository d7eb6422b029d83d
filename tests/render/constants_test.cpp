// The reference rasterizer's constants, which the shaders and the C++ reference both take from
// include/vksplat/constants.hpp: a wrong value would make both disagree with the CUDA renderer.
#include <gtest/gtest.h>

#include "vksplat/constants.hpp"

namespace {

TEST(Constants, MatchTheReferenceRasterizer) {
    namespace c = vksplat::constants;
    // The values of graphdeco-inria diff-gaussian-rasterization (forward.cu, auxiliary.h).
    EXPECT_EQ(c::kTileWidth, 16u);
    EXPECT_EQ(c::kTileHeight, 16u);
    EXPECT_FLOAT_EQ(c::kNearPlane, 0.2f);
    EXPECT_FLOAT_EQ(c::kJacobianClamp, 1.3f);
    EXPECT_FLOAT_EQ(c::kLowPassFilter, 0.3f);
    EXPECT_FLOAT_EQ(c::kEigenvalueFloor, 0.1f);
    EXPECT_FLOAT_EQ(c::kRadiusSigmas, 3.0f);
    EXPECT_FLOAT_EQ(c::kMaxAlpha, 0.99f);
    EXPECT_FLOAT_EQ(c::kMinAlpha, 1.0f / 255.0f);
    EXPECT_FLOAT_EQ(c::kMinTransmittance, 1e-4f);
    EXPECT_FLOAT_EQ(c::kColorOffset, 0.5f);
}

}  // namespace
