// The antimatter15 .splat format: hand-made records decode as the layout says, a written cloud reads
// back within the format's quantisation, and malformed files are refused with a useful message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io::test {
namespace {

std::string record(const float position[3], const float scale[3], const uint8_t rgba[4], const uint8_t rotation[4]) {
    std::string bytes;
    for (int a = 0; a < 3; ++a) append(bytes, position[a]);
    for (int a = 0; a < 3; ++a) append(bytes, scale[a]);
    for (int a = 0; a < 4; ++a) bytes += static_cast<char>(rgba[a]);
    for (int a = 0; a < 4; ++a) bytes += static_cast<char>(rotation[a]);
    return bytes;
}

// Values a .splat can hold without clamping: colours within [0, 1], any opacity and rotation.
GaussianCloud splat_representable_cloud(size_t count, int sh_degree, unsigned seed) {
    GaussianCloud cloud = random_cloud(count, sh_degree, seed);
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> dc(-1.7f, 1.7f);
    for (size_t i = 0; i < count; ++i)
        for (size_t a = 0; a < 3; ++a) cloud.sh[i * cloud.sh_coefficients() * 3 + a] = dc(random);
    return cloud;
}

TEST(FormatsSplat, HandMadeRecordsDecodeAsTheLayoutSays) {
    ScratchDir dir;
    const float position[3] = {1.5f, -2.0f, 3.25f};
    const float scale[3] = {0.5f, 1.0f, 2.0f};
    const uint8_t rgba[4] = {255, 0, 128, 64};
    const uint8_t rotation[4] = {128 + 64, 128, 128, 128 + 64};  // (0.5, 0, 0, 0.5) before normalising
    const uint8_t opaque[4] = {10, 20, 30, 255};
    const uint8_t zero_rotation[4] = {128, 128, 128, 128};
    const uint8_t clear[4] = {10, 20, 30, 0};
    write_bytes(dir / "two.splat", record(position, scale, rgba, rotation) + record(position, scale, opaque, zero_rotation) +
                                       record(position, scale, clear, rotation));
    std::vector<std::string> notes;
    const GaussianCloud cloud = read_splat(dir / "two.splat", &notes);
    ASSERT_EQ(cloud.size(), 3u);
    EXPECT_EQ(cloud.sh_degree, 0);
    EXPECT_NO_THROW(cloud.check_consistent());
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(cloud.positions[a], position[a]);
        EXPECT_FLOAT_EQ(cloud.log_scales[a], std::log(scale[a]));
        EXPECT_FLOAT_EQ(cloud.sh[a], static_cast<float>((rgba[a] / 255.0 - 0.5) / kShC0));
    }
    EXPECT_FLOAT_EQ(cloud.opacity_logits[0], static_cast<float>(std::log((64 / 255.0) / (1 - 64 / 255.0))));
    EXPECT_NEAR(cloud.rotations[0], std::sqrt(0.5), 1e-6);
    EXPECT_EQ(cloud.rotations[1], 0.0f);
    EXPECT_EQ(cloud.rotations[2], 0.0f);
    EXPECT_NEAR(cloud.rotations[3], std::sqrt(0.5), 1e-6);
    // Alpha 255 and 0 have infinite logits: they become the clamp sanitize() would apply.
    EXPECT_EQ(cloud.opacity_logits[1], kMaxOpacityLogit);
    EXPECT_EQ(cloud.opacity_logits[2], -kMaxOpacityLogit);
    // An all-zero quaternion becomes the identity, with a note.
    EXPECT_EQ(std::vector<float>(cloud.rotations.begin() + 4, cloud.rotations.begin() + 8),
              (std::vector<float>{1, 0, 0, 0}));
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("all-zero quaternion"), std::string::npos) << notes[0];
}

TEST(FormatsSplat, RoundTripWithinQuantisation) {
    ScratchDir dir;
    const GaussianCloud original = splat_representable_cloud(500, 2, 7);
    write_splat(original, dir / "scene.splat");
    EXPECT_EQ(std::filesystem::file_size(dir / "scene.splat"), 500u * 32u);
    const GaussianCloud back = read_splat(dir / "scene.splat");
    ASSERT_EQ(back.size(), original.size());
    EXPECT_EQ(back.sh_degree, 0);  // .splat holds the DC colour only
    const size_t k = static_cast<size_t>(original.sh_coefficients());
    for (size_t i = 0; i < original.size(); ++i) {
        for (size_t a = 0; a < 3; ++a) {
            EXPECT_EQ(back.positions[i * 3 + a], original.positions[i * 3 + a]);
            EXPECT_NEAR(back.log_scales[i * 3 + a], original.log_scales[i * 3 + a], 1e-6);
            // Colour is one byte of 0.5 + SH_C0 * dc: half a step is 0.5 / 255 / SH_C0.
            EXPECT_NEAR(back.sh[i * 3 + a], original.sh[i * k * 3 + a], 0.5 / 255 / kShC0 + 1e-6);
        }
        EXPECT_NEAR(sigmoid(back.opacity_logits[i]), sigmoid(original.opacity_logits[i]), 0.5 / 255 + 1e-6);
        // The quaternion comes back normalised, each component within about a step of 1/128.
        double norm = 0, dot = 0;
        for (size_t a = 0; a < 4; ++a) norm += double(original.rotations[i * 4 + a]) * original.rotations[i * 4 + a];
        norm = std::sqrt(norm);
        for (size_t a = 0; a < 4; ++a) {
            EXPECT_NEAR(back.rotations[i * 4 + a], original.rotations[i * 4 + a] / norm, 0.012) << "Gaussian " << i;
            dot += back.rotations[i * 4 + a] * original.rotations[i * 4 + a] / norm;
        }
        EXPECT_GT(dot, 0.9998);
    }
}

TEST(FormatsSplat, WriterClampsAndReplacesDegenerateRotations) {
    ScratchDir dir;
    GaussianCloud cloud;
    cloud.resize(1);
    cloud.sh = {10.0f, -10.0f, 0.0f};  // colours beyond [0, 1] clamp to 255 and 0
    cloud.opacity_logits = {100.0f};
    cloud.rotations = {0, 0, 0, 0};
    write_splat(cloud, dir / "clamped.splat");
    const std::string bytes = read_bytes(dir / "clamped.splat");
    ASSERT_EQ(bytes.size(), 32u);
    EXPECT_EQ(static_cast<uint8_t>(bytes[24]), 255);
    EXPECT_EQ(static_cast<uint8_t>(bytes[25]), 0);
    EXPECT_EQ(static_cast<uint8_t>(bytes[26]), 128);
    EXPECT_EQ(static_cast<uint8_t>(bytes[27]), 255);
    EXPECT_EQ(static_cast<uint8_t>(bytes[28]), 255);  // w = 1 -> 256, clamped
    EXPECT_EQ(static_cast<uint8_t>(bytes[29]), 128);
}

TEST(FormatsSplat, EmptyFileIsAnEmptyCloud) {
    ScratchDir dir;
    write_bytes(dir / "empty.splat", "");
    EXPECT_TRUE(read_splat(dir / "empty.splat").empty());
    write_splat(GaussianCloud{}, dir / "written.splat");
    EXPECT_EQ(std::filesystem::file_size(dir / "written.splat"), 0u);
}

TEST(FormatsSplat, TruncatedFileNamesTheFileAndTheProblem) {
    ScratchDir dir;
    write_bytes(dir / "cut.splat", std::string(32 * 3 + 17, '\x40'));
    expect_input_error([&] { read_splat(dir / "cut.splat"); },
                       {"cut.splat", "113 bytes", "not a multiple of the 32-byte record", "17 bytes"});
}

TEST(FormatsSplat, MissingFile) {
    ScratchDir dir;
    expect_input_error([&] { read_splat(dir / "absent.splat"); }, {"absent.splat", "no such file"});
}

TEST(FormatsSplat, WriterRefusesToReplaceAFileUnlessAsked) {
    ScratchDir dir;
    const GaussianCloud cloud = splat_representable_cloud(3, 0, 2);
    write_splat(cloud, dir / "a.splat");
    expect_input_error([&] { write_splat(cloud, dir / "a.splat"); }, {"a.splat"});
    EXPECT_NO_THROW(write_splat(cloud, dir / "a.splat", WriteMode::overwrite));
}

TEST(FormatsSplat, WriterRefusesAnInconsistentCloud) {
    ScratchDir dir;
    GaussianCloud cloud = splat_representable_cloud(3, 0, 2);
    cloud.positions.pop_back();
    expect_input_error([&] { write_splat(cloud, dir / "bad.splat"); }, {"bad.splat", "inconsistent"});
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.splat"));
}

}  // namespace
}  // namespace vksplat::io::test
