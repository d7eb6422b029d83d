// The GLSL constants header and its C++ twin must agree: they are the reference rasterizer's
// constants, and a drift between them would make the GPU and the tests disagree silently.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "vksplat/constants.hpp"

namespace {

// name -> value of every `const <type> NAME = <expr>;` line, with "a / b" evaluated.
std::map<std::string, double> parse_glsl_constants(const std::string& path) {
    std::ifstream file(path);
    EXPECT_TRUE(file) << "cannot open " << path;
    std::stringstream text;
    text << file.rdbuf();
    const std::regex line(R"(const\s+(?:uint|float|int)\s+(\w+)\s*=\s*([0-9.eE+-]+)\s*(?:/\s*([0-9.eE+-]+))?\s*;)");
    std::map<std::string, double> values;
    const std::string s = text.str();
    for (std::sregex_iterator it(s.begin(), s.end(), line), end; it != end; ++it) {
        double value = std::stod((*it)[2]);
        if ((*it)[3].matched) value /= std::stod((*it)[3]);
        values[(*it)[1]] = value;
    }
    return values;
}

TEST(Constants, GlslAndCppAgree) {
    namespace c = vksplat::constants;
    const auto glsl = parse_glsl_constants(VKSPLAT_SOURCE_DIR "/shaders/include/constants.glsl");
    const std::map<std::string, double> cpp = {
        {"TILE_WIDTH", c::kTileWidth},         {"TILE_HEIGHT", c::kTileHeight},
        {"NEAR_PLANE", c::kNearPlane},         {"JACOBIAN_CLAMP", c::kJacobianClamp},
        {"LOW_PASS_FILTER", c::kLowPassFilter}, {"EIGENVALUE_FLOOR", c::kEigenvalueFloor},
        {"RADIUS_SIGMAS", c::kRadiusSigmas},   {"MAX_ALPHA", c::kMaxAlpha},
        {"MIN_ALPHA", c::kMinAlpha},           {"MIN_TRANSMITTANCE", c::kMinTransmittance},
        {"COLOR_OFFSET", c::kColorOffset},
    };
    EXPECT_EQ(glsl.size(), cpp.size()) << "the GLSL header and constants.hpp list different constants";
    for (const auto& [name, value] : cpp) {
        ASSERT_TRUE(glsl.count(name)) << name << " is missing from constants.glsl";
        EXPECT_FLOAT_EQ(float(glsl.at(name)), float(value)) << name;
    }
}

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
