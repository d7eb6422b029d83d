// Niantic SPZ: files built byte by byte decode as the specification says (versions 2, 3 and 4), a
// written cloud (version 3 by default, 4 on request) reads back within SPZ's quantisation, the fixture made by splat-transform decodes to
// what splat-transform decoded, and malformed files are refused with a useful message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "io/formats_detail.hpp"
#include "io/io_test_helpers.hpp"
#include "io/zstd_frames.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

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

// Version 4 around `attributes` (the blocks of version 3, back to back, of `sizes` bytes each): the
// 32-byte header, `extensions`, the table of contents and one zstd frame per non-empty block.
std::string v4_file(uint32_t count, uint8_t sh_degree, const std::string& attributes, std::vector<size_t> sizes,
                    const std::string& extensions = "", uint8_t flags = 0) {
    std::string bytes = spz_header(4, count, sh_degree, 12, flags | (extensions.empty() ? 0 : 0x2));
    std::vector<std::string> frames;
    std::vector<size_t> stream_sizes;
    size_t offset = 0;
    for (size_t size : sizes) {
        if (size) frames.push_back(detail::zstd_compress(attributes.substr(offset, size), 3, "test"));
        if (size) stream_sizes.push_back(size);
        offset += size;
    }
    bytes[15] = static_cast<char>(frames.size());
    append(bytes, static_cast<uint32_t>(32 + extensions.size()));
    bytes.resize(32, '\0');
    bytes += extensions;
    for (size_t f = 0; f < frames.size(); ++f) {
        append(bytes, static_cast<uint64_t>(frames[f].size()));
        append(bytes, static_cast<uint64_t>(stream_sizes[f]));
    }
    for (const auto& frame : frames) bytes += frame;
    return bytes;
}

// Two splats of SH degree 1 as version 3/4 attribute blocks, and the blocks' sizes.
std::string two_splats_attributes() {
    std::string raw = fixed24(1.5, 12) + fixed24(-2.25, 12) + fixed24(3, 12);
    raw += fixed24(-4, 12) + fixed24(5, 12) + fixed24(0.5, 12);
    raw += block({255, 51}) + block({128, 0, 255, 64, 191, 38}) + block({160, 0, 255, 100, 101, 102});
    append(raw, 3u << 30);
    append(raw, (0u << 30) | (511u << 20) | ((1u << 9 | 100u) << 10) | 0u);
    for (int i = 0; i < 2 * 9; ++i) raw += static_cast<char>(i * 14);
    return raw;
}
const std::vector<size_t> kTwoSplatsBlocks = {18, 2, 6, 6, 8, 18};

std::string extension_record(uint32_t type, const std::string& payload) {
    std::string bytes;
    append(bytes, type);
    append(bytes, static_cast<uint32_t>(payload.size()));
    return bytes + payload;
}

std::string u32_bytes(uint32_t value) {
    std::string bytes;
    append(bytes, value);
    return bytes;
}

TEST(FormatsSpz, Version4DecodesAsVersion3Does) {
    ScratchDir dir;
    const std::string attributes = two_splats_attributes();
    write_bytes(dir / "v3.spz", gzip(spz_header(3, 2, 1) + attributes));
    write_bytes(dir / "v4.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks));
    const GaussianCloud v4 = read_spz(dir / "v4.spz");
    expect_same_cloud(v4, read_spz(dir / "v3.spz"));
    EXPECT_EQ(std::vector<float>(v4.positions.begin(), v4.positions.begin() + 3), (std::vector<float>{1.5f, 2.25f, -3}));
    EXPECT_EQ(read_scene(dir / "v4.spz").size(), 2u);
}

TEST(FormatsSpz, Version4CoordinateSystemExtensionIsHonoured) {
    ScratchDir dir;
    const std::string attributes = two_splats_attributes();
    write_bytes(dir / "plain.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks));
    const GaussianCloud rub = read_spz(dir / "plain.spz");
    // Declared RUB is the default; RDF is the cloud's own axes: nothing turns.
    write_bytes(dir / "rub.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks, extension_record(0xADBE0003, u32_bytes(4))));
    expect_same_cloud(read_spz(dir / "rub.spz"), rub);
    write_bytes(dir / "rdf.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks, extension_record(0xADBE0003, u32_bytes(6))));
    const GaussianCloud rdf = read_spz(dir / "rdf.spz");
    EXPECT_EQ(std::vector<float>(rdf.positions.begin(), rdf.positions.begin() + 3), (std::vector<float>{1.5f, -2.25f, 3}));
    EXPECT_EQ(rdf.rotations[6], -rub.rotations[6]);
    EXPECT_EQ(rdf.sh[3], -rub.sh[3]);  // degree 1, basis y: odd in the turn
    EXPECT_EQ(rdf.sh[9], rub.sh[9]);   // basis x: even
    // Any other system is refused; other extensions are skipped with a note.
    write_bytes(dir / "ruf.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks, extension_record(0xADBE0003, u32_bytes(8))));
    expect_input_error([&] { read_spz(dir / "ruf.spz"); }, {"ruf.spz", "coordinate system 8", "RUB (4) and RDF (6)"});
    write_bytes(dir / "other.spz",
                v4_file(2, 1, attributes, kTwoSplatsBlocks, extension_record(0x12340001, "abc") +
                                                                extension_record(0xADBE0002, std::string(12, '\0'))));
    std::vector<std::string> notes;
    expect_same_cloud(read_spz(dir / "other.spz", &notes), rub);
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("ignored SPZ extension 0x12340001"), std::string::npos) << notes[0];
    EXPECT_NE(notes[1].find("SPZ_ADOBE_safe_orbit_camera"), std::string::npos) << notes[1];
    write_bytes(dir / "cut.spz", v4_file(2, 1, attributes, kTwoSplatsBlocks, extension_record(0x12340001, "abc").substr(0, 9)));
    expect_input_error([&] { read_spz(dir / "cut.spz"); }, {"cut.spz", "extension 0x12340001", "says 3 bytes"});
}

TEST(FormatsSpzErrors, MalformedVersion4IsRefused) {
    ScratchDir dir;
    const std::string attributes = two_splats_attributes();
    const std::string good = v4_file(2, 1, attributes, kTwoSplatsBlocks);
    const auto refuse = [&](const std::string& name, const std::string& bytes, const std::vector<std::string>& parts) {
        write_bytes(dir / name, bytes);
        std::vector<std::string> expected = parts;
        expected.insert(expected.begin(), name);
        expect_input_error([&] { read_spz(dir / name); }, expected);
    };
    refuse("header.spz", good.substr(0, 20), {"truncated", "32 bytes"});
    refuse("long.spz", good + "x", {"1 bytes follow the last attribute stream"});
    refuse("cut.spz", good.substr(0, good.size() - 3), {"truncated", "attribute stream 5"});
    std::string streams = good;
    streams[15] = 5;
    refuse("streams.spz", streams, {"5 attribute streams", "which are 6"});
    std::string toc = good;
    std::memset(toc.data() + 16, 0xff, 4);
    refuse("toc.spz", toc, {"table of contents starts at byte 4294967295"});
    // The count disagrees with the streams' sizes: refused before anything is allocated for it.
    std::string count = good;
    const uint32_t huge = 0xffffffffu;
    std::memcpy(count.data() + 8, &huge, 4);
    refuse("count.spz", count, {"attribute stream 0 holds 18 bytes", "4294967295 splats"});
    // A frame that holds fewer bytes than its table entry says.
    refuse("short.spz", v4_file(2, 1, attributes.substr(0, attributes.size() - 1), {18, 2, 6, 6, 8, 17}),
           {"attribute stream 5 holds 17 bytes", "18 of them"});
    std::string corrupt = good;
    corrupt[32 + 6 * 16] ^= 0x5a;  // the first frame's magic
    refuse("corrupt.spz", corrupt, {"attribute stream 0", "corrupt compressed data (zstd"});
}

// A cloud whose values SPZ can hold: DC within its colour range, log scales within [-10, 5.9],
// SH within [-1, 1).
GaussianCloud spz_representable_cloud(size_t count, int sh_degree, unsigned seed) {
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

// Both versions hold the same values: positions to half of 1/4096, log scales to 1/32, DC to half of
// 1/(0.15 * 255), SH to 1/256, opacity to 0.5/255 after the sigmoid, rotations to 0.003 a component.
TEST(FormatsSpz, RoundTripWithinQuantisation) {
    ScratchDir dir;
    for (int version : {3, 4})
        for (int degree = 0; degree <= 3; ++degree) {
            const GaussianCloud original = spz_representable_cloud(300, degree, 11 + degree);
            const auto path = dir / ("scene" + std::to_string(version) + std::to_string(degree) + ".spz");
            write_spz(original, path, WriteMode::refuse_existing, version);
            const std::string bytes = read_bytes(path);
            ASSERT_GE(bytes.size(), 32u);
            if (version == 3) {
                EXPECT_EQ(static_cast<uint8_t>(bytes[0]), 0x1f);  // gzip
                EXPECT_EQ(static_cast<uint8_t>(bytes[1]), 0x8b);
            } else {
                EXPECT_EQ(bytes.substr(0, 4), "NGSP");
                EXPECT_EQ(bytes[4], 4);
                EXPECT_EQ(bytes[15], degree ? 6 : 5);  // attribute streams: no SH stream at degree 0
            }
            const GaussianCloud back = read_spz(path);
            expect_within_spz_quantisation(original, back, 1.0 / 4096);
        }
}

TEST(FormatsSpz, WriterWritesVersion3UnlessAskedFor4) {
    ScratchDir dir;
    const GaussianCloud cloud = spz_representable_cloud(5, 1, 3);
    write_spz(cloud, dir / "default.spz");
    EXPECT_EQ(static_cast<uint8_t>(read_bytes(dir / "default.spz")[0]), 0x1f);
    write_scene(cloud, dir / "named.spz", WriteMode::refuse_existing, "spz-v4");
    EXPECT_EQ(read_bytes(dir / "named.spz").substr(0, 5), std::string("NGSP\x04"));
    expect_input_error([&] { write_spz(cloud, dir / "v2.spz", WriteMode::refuse_existing, 2); },
                       {"v2.spz", "cannot write SPZ version 2"});
}

TEST(FormatsSpz, WriterUsesFewerFractionalBitsForLargeScenes) {
    ScratchDir dir;
    GaussianCloud original = spz_representable_cloud(20, 1, 5);
    original.positions[7] = 30000.0f;  // needs 15 integer bits: at most 8 fractional
    write_spz(original, dir / "large.spz", WriteMode::refuse_existing, 4);
    const std::string header = read_bytes(dir / "large.spz");  // version 4: the header is not compressed
    EXPECT_EQ(static_cast<int>(header[13]), 8);
    EXPECT_EQ(static_cast<int>(header[4]), 4);
    expect_within_spz_quantisation(original, read_spz(dir / "large.spz"), 1.0 / 256);
}

TEST(FormatsSpz, WriterRefusesWhatSpzCannotHold) {
    ScratchDir dir;
    GaussianCloud cloud = spz_representable_cloud(3, 0, 1);
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
    for (int version : {3, 4}) {
        const auto path = dir / ("empty" + std::to_string(version) + ".spz");
        write_spz(empty, path, WriteMode::refuse_existing, version);
        const GaussianCloud back = read_spz(path);
        EXPECT_TRUE(back.empty());
        EXPECT_EQ(back.sh_degree, 2);
    }
    EXPECT_EQ(read_bytes(dir / "empty4.spz").size(), 32u);  // the header alone: no streams
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
    for (uint32_t version : {0u, 1u, 77u}) {
        std::string raw = valid_raw(2);
        std::memcpy(raw.data() + 4, &version, 4);
        write_bytes(dir / "version.spz", gzip(raw));
        expect_input_error([&] { read_spz(dir / "version.spz"); },
                           {"version.spz", "unsupported SPZ version " + std::to_string(version), "2, 3 and 4"});
    }
    std::string raw = valid_raw(2);
    raw[4] = 4;
    write_bytes(dir / "gzipped4.spz", gzip(raw));
    expect_input_error([&] { read_spz(dir / "gzipped4.spz"); }, {"gzipped4.spz", "version 4 files are not gzipped"});
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
