// Niantic SPZ: files built byte by byte decode as the specification says (versions 2 and 3), a
// written cloud reads back within SPZ's quantisation, the fixture made by splat-transform decodes to
// what splat-transform decoded, and malformed files are refused with a useful message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "io/formats_detail.hpp"
#include "io/io_test_helpers.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

double sigmoid(double x) { return 1.0 / (1.0 + std::exp(-x)); }

template <typename T>
void append(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
}

std::string spz_header(uint32_t version, uint32_t count, uint8_t sh_degree, uint8_t fractional_bits = 12,
                       uint8_t flags = 0, uint32_t magic = 0x5053474e) {
    std::string bytes;
    append(bytes, magic);
    append(bytes, version);
    append(bytes, count);
    bytes += static_cast<char>(sh_degree);
    bytes += static_cast<char>(fractional_bits);
    bytes += static_cast<char>(flags);
    bytes += '\0';
    return bytes;
}

std::string gzip(const std::string& raw) {
    return detail::deflate_bytes(raw, detail::Inflater::Wrapping::gzip, "test");
}

// Bytes of one attribute block: `values` per splat.
std::string block(std::initializer_list<int> values) {
    std::string bytes;
    for (int v : values) bytes += static_cast<char>(static_cast<uint8_t>(v));
    return bytes;
}

// A 24-bit little-endian fixed-point coordinate.
std::string fixed24(double value, int fractional_bits) {
    const auto fixed = static_cast<int32_t>(std::lround(std::ldexp(value, fractional_bits)));
    return block({fixed & 0xff, (fixed >> 8) & 0xff, (fixed >> 16) & 0xff});
}

TEST(FormatsSpz, Version2DecodesByHand) {
    ScratchDir dir;
    // Two splats, SH degree 1, 10 fractional bits.
    std::string raw = spz_header(2, 2, 1, 10);
    raw += fixed24(1.5, 10) + fixed24(-2.25, 10) + fixed24(100.0, 10);      // splat 0
    raw += fixed24(-0.0009765625, 10) + fixed24(0, 10) + fixed24(-4096, 10);  // splat 1
    raw += block({255, 51});                                                  // alphas
    raw += block({128, 0, 255, 64, 191, 38});                                 // colours
    raw += block({160, 0, 255, 100, 101, 102});                               // scales
    raw += block({128, 128, 128, 255, 128, 128});                             // rotations (x, y, z)
    std::string sh;
    for (int i = 0; i < 2 * 9; ++i) sh += static_cast<char>(i * 14);
    raw += sh;
    write_bytes(dir / "v2.spz", gzip(raw));

    const GaussianCloud cloud = read_spz(dir / "v2.spz");
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud.sh_degree, 1);
    // SPZ is RUB (y up, z back), the cloud RDF: y and z change sign.
    EXPECT_EQ(cloud.positions, (std::vector<float>{1.5f, 2.25f, -100.0f, -0.0009765625f, 0.0f, 4096.0f}));
    EXPECT_FLOAT_EQ(cloud.log_scales[0], 0.0f);  // 160 / 16 - 10
    EXPECT_FLOAT_EQ(cloud.log_scales[1], -10.0f);
    EXPECT_FLOAT_EQ(cloud.log_scales[2], 255 / 16.0f - 10);
    EXPECT_EQ(cloud.opacity_logits[0], kMaxOpacityLogit);
    EXPECT_FLOAT_EQ(cloud.opacity_logits[1], static_cast<float>(std::log(0.2 / 0.8)));
    const double colours[6] = {128, 0, 255, 64, 191, 38};
    for (size_t i = 0; i < 2; ++i)
        for (size_t a = 0; a < 3; ++a)
            EXPECT_FLOAT_EQ(cloud.sh[i * 12 + a], static_cast<float>((colours[i * 3 + a] / 255 - 0.5) / 0.15));
    for (size_t i = 0; i < 2; ++i)
        for (size_t k = 0; k < 9; ++k)
            EXPECT_FLOAT_EQ(cloud.sh[i * 12 + 3 + k],
                            (k < 6 ? -1 : 1) *  // degree 1 basis y, z, x: the first two flip
                                static_cast<float>((static_cast<double>((i * 9 + k) * 14) - 128) / 128.0));
    // (128, 128, 128) is x = y = z = 1/255: nearly the identity; 255 is x = 1 and w = 0.
    EXPECT_NEAR(cloud.rotations[0], 1.0f, 1e-4);
    EXPECT_NEAR(cloud.rotations[1], 128 / 127.5 - 1, 1e-7);
    EXPECT_NEAR(cloud.rotations[2], -(128 / 127.5 - 1), 1e-7);  // y and z flip with the axes
    EXPECT_NEAR(cloud.rotations[4], 0.0f, 1e-6);
    EXPECT_FLOAT_EQ(cloud.rotations[5], 1.0f);
}

TEST(FormatsSpz, Version3SmallestThreeRotationsDecodeByHand) {
    ScratchDir dir;
    const uint32_t identity = 3u << 30;  // w largest, x = y = z = 0
    // x largest; then y (highest bits), z, w: y = +sqrt(1/2) (magnitude 511), z = -sqrt(1/2) * 100/511, w = 0.
    const uint32_t mixed = (0u << 30) | (511u << 20) | ((1u << 9 | 100u) << 10) | 0u;
    std::string raw = spz_header(3, 2, 0);
    raw += fixed24(0, 12) + fixed24(0, 12) + fixed24(0, 12) + fixed24(1, 12) + fixed24(2, 12) + fixed24(3, 12);
    raw += block({0, 128});
    raw += block({128, 128, 128, 128, 128, 128});
    raw += block({160, 160, 160, 160, 160, 160});
    append(raw, identity);
    append(raw, mixed);
    write_bytes(dir / "v3.spz", gzip(raw));

    const GaussianCloud cloud = read_spz(dir / "v3.spz");
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud.sh_degree, 0);
    EXPECT_EQ(std::vector<float>(cloud.rotations.begin(), cloud.rotations.begin() + 4), (std::vector<float>{1, 0, 0, 0}));
    const double y = std::sqrt(0.5), z = -std::sqrt(0.5) * 100 / 511;
    const double x = std::sqrt(1 - y * y - z * z);
    EXPECT_NEAR(cloud.rotations[4], 0.0, 1e-7);  // w
    EXPECT_NEAR(cloud.rotations[5], x, 1e-6);
    EXPECT_NEAR(cloud.rotations[6], -y, 1e-6);  // RUB -> RDF
    EXPECT_NEAR(cloud.rotations[7], -z, 1e-6);
    EXPECT_EQ(cloud.opacity_logits[0], -kMaxOpacityLogit);
    EXPECT_EQ(cloud.positions[5], -3.0f);
}

TEST(FormatsSpz, UncompressedStreamIsAccepted) {
    ScratchDir dir;
    std::string raw = spz_header(3, 1, 0);
    raw += fixed24(1, 12) + fixed24(2, 12) + fixed24(3, 12) + block({128, 128, 128, 128, 160, 160, 160});
    append(raw, 3u << 30);
    write_bytes(dir / "plain.spz", raw);
    EXPECT_EQ(read_spz(dir / "plain.spz").positions, (std::vector<float>{1, -2, -3}));
}

// A cloud whose values SPZ can hold: DC within its colour range, log scales within [-10, 5.9],
// SH within [-1, 1).
GaussianCloud representable_cloud(size_t count, int sh_degree, unsigned seed) {
    GaussianCloud cloud = random_cloud(count, sh_degree, seed);
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(-0.99f, 0.99f);
    std::uniform_real_distribution<float> position(-100.0f, 100.0f);
    std::uniform_real_distribution<float> log_scale(-9.0f, 5.0f);
    for (float& v : cloud.positions) v = position(random);
    for (float& v : cloud.log_scales) v = log_scale(random);
    const size_t k = static_cast<size_t>(cloud.sh_coefficients());
    for (size_t i = 0; i < count; ++i)
        for (size_t c = 0; c < k * 3; ++c) cloud.sh[i * k * 3 + c] = unit(random) * (c < 3 ? 3.0f : 1.0f);
    return cloud;
}

void expect_within_spz_quantisation(const GaussianCloud& original, const GaussianCloud& back, double position_step) {
    ASSERT_EQ(back.size(), original.size());
    ASSERT_EQ(back.sh_degree, original.sh_degree);
    const size_t k = static_cast<size_t>(original.sh_coefficients());
    for (size_t i = 0; i < original.size(); ++i) {
        for (size_t a = 0; a < 3; ++a) {
            EXPECT_NEAR(back.positions[i * 3 + a], original.positions[i * 3 + a], position_step / 2 * 1.001);
            EXPECT_NEAR(back.log_scales[i * 3 + a], original.log_scales[i * 3 + a], 1.0 / 32 + 1e-6);
        }
        for (size_t c = 0; c < k * 3; ++c) {
            const double step = c < 3 ? 1.0 / (0.15 * 255) : 1.0 / 128;
            EXPECT_NEAR(back.sh[i * k * 3 + c], original.sh[i * k * 3 + c], step / 2 + 1e-6) << "Gaussian " << i;
        }
        EXPECT_NEAR(sigmoid(back.opacity_logits[i]), sigmoid(original.opacity_logits[i]), 0.5 / 255 + 1e-6);
        // Smallest three: each small component within sqrt(1/2) / 511 / 2; q and -q are the same.
        double norm = 0, dot = 0;
        for (size_t a = 0; a < 4; ++a) norm += double(original.rotations[i * 4 + a]) * original.rotations[i * 4 + a];
        for (size_t a = 0; a < 4; ++a) dot += back.rotations[i * 4 + a] * original.rotations[i * 4 + a] / std::sqrt(norm);
        const double sign = dot < 0 ? -1 : 1;
        for (size_t a = 0; a < 4; ++a)
            EXPECT_NEAR(sign * back.rotations[i * 4 + a], original.rotations[i * 4 + a] / std::sqrt(norm), 0.003);
    }
}

TEST(FormatsSpz, RoundTripWithinQuantisation) {
    ScratchDir dir;
    for (int degree = 0; degree <= 3; ++degree) {
        const GaussianCloud original = representable_cloud(300, degree, 11 + degree);
        const auto path = dir / ("scene" + std::to_string(degree) + ".spz");
        write_spz(original, path);
        const std::string bytes = read_bytes(path);
        ASSERT_GE(bytes.size(), 2u);
        EXPECT_EQ(static_cast<uint8_t>(bytes[0]), 0x1f);  // gzip
        EXPECT_EQ(static_cast<uint8_t>(bytes[1]), 0x8b);
        const GaussianCloud back = read_spz(path);
        expect_within_spz_quantisation(original, back, 1.0 / 4096);
    }
}

TEST(FormatsSpz, WriterUsesFewerFractionalBitsForLargeScenes) {
    ScratchDir dir;
    GaussianCloud original = representable_cloud(20, 1, 5);
    original.positions[7] = 30000.0f;  // needs 15 integer bits: at most 8 fractional
    write_spz(original, dir / "large.spz");
    const std::string compressed = read_bytes(dir / "large.spz");
    detail::Inflater inflater(compressed, detail::Inflater::Wrapping::gzip, "large.spz");
    std::string header;
    inflater.read(header, 16);
    EXPECT_EQ(static_cast<int>(header[13]), 8);
    EXPECT_EQ(static_cast<int>(header[4]), 3);  // version 3
    expect_within_spz_quantisation(original, read_spz(dir / "large.spz"), 1.0 / 256);
}

TEST(FormatsSpz, WriterRefusesWhatSpzCannotHold) {
    ScratchDir dir;
    GaussianCloud cloud = representable_cloud(3, 0, 1);
    cloud.positions[4] = 1e7f;
    expect_input_error([&] { write_spz(cloud, dir / "huge.spz"); }, {"huge.spz", "24-bit fixed point"});
    cloud.positions[4] = std::nanf("");
    expect_input_error([&] { write_spz(cloud, dir / "nan.spz"); }, {"nan.spz", "Gaussian 1", "not finite"});
    EXPECT_FALSE(std::filesystem::exists(dir / "nan.spz"));
}

TEST(FormatsSpz, EmptyCloudRoundTrips) {
    ScratchDir dir;
    GaussianCloud empty;
    empty.sh_degree = 2;
    write_spz(empty, dir / "empty.spz");
    const GaussianCloud back = read_spz(dir / "empty.spz");
    EXPECT_TRUE(back.empty());
    EXPECT_EQ(back.sh_degree, 2);
}

// One valid version 3 file of `count` splats of degree 1, uncompressed.
std::string valid_raw(uint32_t count) {
    std::string raw = spz_header(3, count, 1);
    raw += std::string(count * (9 + 1 + 3 + 3 + 4 + 9), '\x10');
    return raw;
}

TEST(FormatsSpzErrors, WrongMagic) {
    ScratchDir dir;
    std::string raw = valid_raw(2);
    raw[0] = 'X';
    write_bytes(dir / "magic.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "magic.spz"); }, {"magic.spz", "wrong magic", "0x5053474e"});
    write_bytes(dir / "text.spz", "hello, this is not an spz file");
    expect_input_error([&] { read_spz(dir / "text.spz"); }, {"text.spz", "not an SPZ file", "wrong magic"});
}

TEST(FormatsSpzErrors, WrongVersion) {
    ScratchDir dir;
    for (uint32_t version : {0u, 1u, 4u, 77u}) {
        std::string raw = valid_raw(2);
        std::memcpy(raw.data() + 4, &version, 4);
        write_bytes(dir / "version.spz", gzip(raw));
        expect_input_error([&] { read_spz(dir / "version.spz"); },
                           {"version.spz", "unsupported SPZ version " + std::to_string(version), "2 and 3"});
    }
}

TEST(FormatsSpzErrors, TruncatedPayload) {
    ScratchDir dir;
    std::string raw = valid_raw(10);
    raw.resize(raw.size() - 5);
    write_bytes(dir / "short.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "short.spz"); },
                       {"short.spz", "truncated", "10 splats", "290 bytes", "only 285"});
}

TEST(FormatsSpzErrors, TruncatedHeader) {
    ScratchDir dir;
    write_bytes(dir / "header.spz", gzip(valid_raw(1).substr(0, 10)));
    expect_input_error([&] { read_spz(dir / "header.spz"); }, {"header.spz", "truncated", "16 bytes"});
}

TEST(FormatsSpzErrors, TruncatedCompressedStream) {
    ScratchDir dir;
    std::string compressed = gzip(valid_raw(1000));
    compressed.resize(compressed.size() / 2);
    write_bytes(dir / "cut.spz", compressed);
    expect_input_error([&] { read_spz(dir / "cut.spz"); }, {"cut.spz", "truncated"});
}

TEST(FormatsSpzErrors, CountThatOverflowsTheDataIsRefusedWithoutAllocatingIt) {
    ScratchDir dir;
    std::string raw = valid_raw(4);
    const uint32_t huge = 0xffffffffu;
    std::memcpy(raw.data() + 8, &huge, 4);
    write_bytes(dir / "huge.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "huge.spz"); }, {"huge.spz", "truncated", "4294967295 splats"});
}

TEST(FormatsSpzErrors, MoreDataThanTheCountSays) {
    ScratchDir dir;
    write_bytes(dir / "long.spz", gzip(valid_raw(3) + "extra"));
    expect_input_error([&] { read_spz(dir / "long.spz"); }, {"long.spz", "does not match", "3 splats"});
}

TEST(FormatsSpzErrors, UnsupportedShDegreeAndExtensions) {
    ScratchDir dir;
    std::string raw = valid_raw(1);
    raw[12] = 4;
    write_bytes(dir / "degree.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "degree.spz"); }, {"degree.spz", "SH degree 4"});
    raw = valid_raw(1);
    raw[14] = 0x2;
    write_bytes(dir / "ext.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "ext.spz"); }, {"ext.spz", "extensions"});
}

TEST(FormatsSpzErrors, MissingFile) {
    ScratchDir dir;
    expect_input_error([&] { read_spz(dir / "absent.spz"); }, {"absent.spz", "no such file"});
}

// The largest difference between two arrays; an infinite expected value (what splat-transform gives
// for alpha 0 and 255) must have become the clamp of the same sign.
double max_difference(const std::vector<float>& ours, const std::vector<float>& expected, float clamp = 0) {
    EXPECT_EQ(ours.size(), expected.size());
    double worst = 0;
    for (size_t i = 0; i < std::min(ours.size(), expected.size()); ++i) {
        if (std::isinf(expected[i]) && clamp > 0) {
            EXPECT_EQ(ours[i], std::copysign(clamp, expected[i])) << i;
            continue;
        }
        worst = std::max(worst, std::abs(double(ours[i]) - expected[i]));
    }
    return worst;
}

TEST(FormatsSpzSharedData, SnowmikuMatchesSplatTransformsDecoding) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto folder = vksplat::test::shared_data_dir() / "formats";
    if (!std::filesystem::exists(folder / "snowmiku.spz")) GTEST_SKIP() << folder / "snowmiku.spz" << " not found";
    const GaussianCloud ours = read_spz(folder / "snowmiku.spz");
    const GaussianCloud expected = read_ply(folder / "snowmiku.spz.decoded.ply");
    ASSERT_EQ(ours.size(), 57694u);
    ASSERT_EQ(ours.sh_degree, 3);
    ASSERT_EQ(expected.size(), ours.size());
    const double position = max_difference(ours.positions, expected.positions);
    const double scale = max_difference(ours.log_scales, expected.log_scales);
    const double rotation = max_difference(ours.rotations, expected.rotations);
    const double opacity = max_difference(ours.opacity_logits, expected.opacity_logits, kMaxOpacityLogit);
    const double sh = max_difference(ours.sh, expected.sh);
    RecordProperty("max_error_position", std::to_string(position));
    RecordProperty("max_error_rotation", std::to_string(rotation));
    std::printf("snowmiku.spz max |ours - splat-transform|: position %.3g, log scale %.3g, rotation %.3g, "
                "opacity %.3g, sh %.3g\n",
                position, scale, rotation, opacity, sh);
    // Both decoders dequantise the same integers: only float rounding may differ.
    EXPECT_LE(position, 1e-6);
    EXPECT_LE(scale, 1e-6);
    EXPECT_LE(rotation, std::sqrt(0.5) / 511);
    EXPECT_LE(opacity, 1e-5);
    EXPECT_LE(sh, 1e-6);
}

TEST(FormatsSpzSharedData, SnowmikuSurvivesOurWriterUnchanged) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto path = vksplat::test::shared_data_dir() / "formats" / "snowmiku.spz";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
    // Re-encoding decoded values gives back the same bytes' values: SPZ -> cloud -> SPZ is lossless.
    ScratchDir dir;
    const GaussianCloud first = read_spz(path);
    write_spz(first, dir / "again.spz");
    const GaussianCloud second = read_spz(dir / "again.spz");
    EXPECT_LE(max_difference(second.positions, first.positions), 1e-6);
    EXPECT_LE(max_difference(second.log_scales, first.log_scales), 1e-6);
    EXPECT_LE(max_difference(second.opacity_logits, first.opacity_logits), 1e-5);
    EXPECT_LE(max_difference(second.sh, first.sh), 1e-6);
    // Rotations are re-packed: equal up to sign (the largest component is made positive again), and
    // where two components tie for largest the other may be chosen, which moves by under a step.
    double rotation = 0;
    for (size_t i = 0; i < first.size(); ++i) {
        double dot = 0;
        for (size_t a = 0; a < 4; ++a) dot += double(first.rotations[i * 4 + a]) * second.rotations[i * 4 + a];
        for (size_t a = 0; a < 4; ++a)
            rotation = std::max(rotation, std::abs((dot < 0 ? -1.0 : 1.0) * second.rotations[i * 4 + a] -
                                                   first.rotations[i * 4 + a]));
    }
    EXPECT_LE(rotation, std::sqrt(0.5) / 511);
}

}  // namespace
}  // namespace vksplat::io::test
