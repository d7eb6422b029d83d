// PlayCanvas compressed PLY: files built by hand (random packed words, chunk ranges) decode to what
// the layout says, the fixture made by splat-transform decodes to what splat-transform decoded,
// read_scene tells the two PLY flavours apart, and malformed files are refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>

#include "io/io_test_helpers.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

const char* const kChunkNames[] = {"min_x",       "min_y",       "min_z",       "max_x",       "max_y",
                                   "max_z",       "min_scale_x", "min_scale_y", "min_scale_z", "max_scale_x",
                                   "max_scale_y", "max_scale_z", "min_r",       "min_g",       "min_b",
                                   "max_r",       "max_g",       "max_b"};

struct CompressedFile {
    bool chunk_colours = true;
    size_t sh_rest = 0;  // f_rest_* bytes per splat: 0, 9, 24 or 45
    std::vector<std::array<float, 18>> chunks;
    std::vector<std::array<uint32_t, 4>> packed;  // position, rotation, scale, colour
    std::vector<std::vector<uint8_t>> sh;

    std::string bytes(const std::string& format = "binary_little_endian") const {
        const size_t chunk_fields = chunk_colours ? 18 : 12;
        std::string text = "ply\nformat " + format + " 1.0\ncomment made by hand\nelement chunk " +
                           std::to_string(chunks.size()) + "\n";
        for (size_t f = 0; f < chunk_fields; ++f) text += std::string("property float ") + kChunkNames[f] + "\n";
        text += "element vertex " + std::to_string(packed.size()) + "\n";
        for (const char* name : {"packed_position", "packed_rotation", "packed_scale", "packed_color"})
            text += std::string("property uint ") + name + "\n";
        if (sh_rest) {
            text += "element sh " + std::to_string(sh.size()) + "\n";
            for (size_t r = 0; r < sh_rest; ++r) text += "property uchar f_rest_" + std::to_string(r) + "\n";
        }
        text += "end_header\n";
        for (const auto& chunk : chunks)
            for (size_t f = 0; f < chunk_fields; ++f) append(text, chunk[f]);
        for (const auto& words : packed)
            for (uint32_t word : words) append(text, word);
        for (const auto& row : sh)
            for (uint8_t b : row) text += static_cast<char>(b);
        return text;
    }
};

CompressedFile random_file(size_t count, bool chunk_colours, size_t sh_rest, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> low(-5.0f, 0.0f), high(0.0f, 5.0f), colour_low(-0.5f, 0.3f),
        colour_high(0.6f, 1.5f);
    CompressedFile file;
    file.chunk_colours = chunk_colours;
    file.sh_rest = sh_rest;
    for (size_t c = 0; c < (count + 255) / 256; ++c) {
        std::array<float, 18> chunk{};
        for (size_t f = 0; f < 3; ++f) {
            chunk[f] = low(random);
            chunk[3 + f] = high(random);
            chunk[6 + f] = low(random) - 5;
            chunk[9 + f] = high(random) - 5;
            chunk[12 + f] = colour_low(random);
            chunk[15 + f] = colour_high(random);
        }
        file.chunks.push_back(chunk);
    }
    for (size_t i = 0; i < count; ++i) {
        file.packed.push_back({static_cast<uint32_t>(random()), static_cast<uint32_t>(random()),
                               static_cast<uint32_t>(random()), static_cast<uint32_t>(random())});
        if (sh_rest) {
            std::vector<uint8_t> row(sh_rest);
            for (auto& b : row) b = static_cast<uint8_t>(random());
            if (i == 0) row[0] = 0, row[1] = 255;  // the two special bytes
            file.sh.push_back(row);
        }
    }
    // Alpha 0 and 255 (infinite logits) on the first splats.
    file.packed[0][3] &= 0xffffff00u;
    if (count > 1) file.packed[1][3] |= 0xffu;
    return file;
}

// The layout, written out independently of the reader.
GaussianCloud expected_cloud(const CompressedFile& file) {
    const auto field = [](uint32_t word, int shift, int bits) {
        return static_cast<double>((word >> shift) & ((1u << bits) - 1)) / ((1u << bits) - 1);
    };
    GaussianCloud cloud;
    const size_t count = file.packed.size();
    cloud.sh_degree = file.sh_rest == 45 ? 3 : file.sh_rest == 24 ? 2 : file.sh_rest == 9 ? 1 : 0;
    cloud.resize(count);
    const size_t k = static_cast<size_t>(cloud.sh_coefficients());
    for (size_t i = 0; i < count; ++i) {
        const auto& chunk = file.chunks[i / 256];
        const auto& w = file.packed[i];
        const double p[3] = {field(w[0], 21, 11), field(w[0], 11, 10), field(w[0], 0, 11)};
        const double s[3] = {field(w[2], 21, 11), field(w[2], 11, 10), field(w[2], 0, 11)};
        for (size_t a = 0; a < 3; ++a) {
            cloud.positions[i * 3 + a] = static_cast<float>(chunk[a] + (chunk[3 + a] - chunk[a]) * p[a]);
            cloud.log_scales[i * 3 + a] = static_cast<float>(chunk[6 + a] + (chunk[9 + a] - chunk[6 + a]) * s[a]);
            const double c = field(w[3], 24 - 8 * static_cast<int>(a), 8);
            const double colour = file.chunk_colours ? chunk[12 + a] + (chunk[15 + a] - chunk[12 + a]) * c : c;
            cloud.sh[i * k * 3 + a] = static_cast<float>((colour - 0.5) / kShC0);
        }
        const double alpha = field(w[3], 0, 8);
        cloud.opacity_logits[i] = alpha == 0   ? -kMaxOpacityLogit
                                  : alpha == 1 ? kMaxOpacityLogit
                                               : static_cast<float>(std::log(alpha / (1 - alpha)));
        double small[3], sum = 0;
        for (int a = 0; a < 3; ++a) {
            small[a] = (field(w[1], 20 - 10 * a, 10) - 0.5) * std::sqrt(2.0);
            sum += small[a] * small[a];
        }
        const uint32_t largest = w[1] >> 30;
        for (uint32_t a = 0, s_index = 0; a < 4; ++a)
            cloud.rotations[i * 4 + a] = static_cast<float>(a == largest ? std::sqrt(std::max(0.0, 1 - sum)) : small[s_index++]);
        for (size_t r = 0; r < file.sh_rest; ++r) {
            const uint8_t b = file.sh[i][r];
            const double unit = b == 0 ? 0 : b == 255 ? 1 : (b + 0.5) / 256;
            const size_t channel = r / (k - 1), coefficient = 1 + r % (k - 1);
            cloud.sh[i * k * 3 + coefficient * 3 + channel] = static_cast<float>(unit * 8 - 4);
        }
    }
    return cloud;
}

void expect_near_clouds(const GaussianCloud& ours, const GaussianCloud& expected, double tolerance) {
    ASSERT_EQ(ours.size(), expected.size());
    ASSERT_EQ(ours.sh_degree, expected.sh_degree);
    const auto near = [&](const std::vector<float>& a, const std::vector<float>& b, const char* what) {
        ASSERT_EQ(a.size(), b.size()) << what;
        for (size_t i = 0; i < a.size(); ++i)
            ASSERT_NEAR(a[i], b[i], tolerance * std::max(1.0f, std::abs(b[i]))) << what << " [" << i << "]";
    };
    near(ours.positions, expected.positions, "positions");
    near(ours.log_scales, expected.log_scales, "log_scales");
    near(ours.rotations, expected.rotations, "rotations");
    near(ours.opacity_logits, expected.opacity_logits, "opacity_logits");
    near(ours.sh, expected.sh, "sh");
}

TEST(FormatsCompressedPly, HandMadeFileWithChunkColoursAndShDecodes) {
    ScratchDir dir;
    const CompressedFile file = random_file(600, true, 24, 3);  // 3 chunks, the last one partial
    write_bytes(dir / "scene.ply", file.bytes());
    EXPECT_TRUE(is_compressed_ply(dir / "scene.ply"));
    const GaussianCloud cloud = read_compressed_ply(dir / "scene.ply");
    EXPECT_NO_THROW(cloud.check_consistent());
    expect_near_clouds(cloud, expected_cloud(file), 1e-6);
    EXPECT_EQ(cloud.opacity_logits[0], -kMaxOpacityLogit);
    EXPECT_EQ(cloud.opacity_logits[1], kMaxOpacityLogit);
    EXPECT_EQ(cloud.sh[3], -4.0f);  // f_rest_0 = 0: red, coefficient 1, the bottom of [-4, 4]
    EXPECT_EQ(cloud.sh[6], 4.0f);   // f_rest_1 = 255: red, coefficient 2, the top
}

TEST(FormatsCompressedPly, HandMadeFileWithoutChunkColoursOrShDecodes) {
    ScratchDir dir;
    const CompressedFile file = random_file(5, false, 0, 4);
    write_bytes(dir / "small.ply", file.bytes());
    expect_near_clouds(read_compressed_ply(dir / "small.ply"), expected_cloud(file), 1e-6);
}

TEST(FormatsCompressedPly, ReadSceneTellsThePlyFlavoursApart) {
    ScratchDir dir;
    const CompressedFile file = random_file(300, true, 9, 5);
    write_bytes(dir / "compressed.ply", file.bytes());
    const GaussianCloud plain = random_cloud(4, 1, 6);
    write_ply(plain, dir / "plain.ply");
    EXPECT_EQ(scene_format_of(dir / "compressed.ply"), "compressed-ply");
    EXPECT_EQ(scene_format_of(dir / "plain.ply"), "ply");
    EXPECT_FALSE(is_compressed_ply(dir / "plain.ply"));
    expect_near_clouds(read_scene(dir / "compressed.ply"), expected_cloud(file), 1e-6);
    expect_near_clouds(read_scene(dir / "compressed.ply", nullptr, "ply"), expected_cloud(file), 1e-6);
    expect_near_clouds(read_scene(dir / "compressed.ply", nullptr, "compressed-ply"), expected_cloud(file), 1e-6);
    expect_same_cloud(read_scene(dir / "plain.ply"), plain);
    expect_input_error([&] { read_compressed_ply(dir / "plain.ply"); }, {"plain.ply", "no 'chunk' element"});
}

TEST(FormatsCompressedPlyErrors, ChunkCountMustMatchTheVertices) {
    ScratchDir dir;
    CompressedFile file = random_file(300, true, 0, 7);
    file.chunks.pop_back();
    write_bytes(dir / "chunks.ply", file.bytes());
    expect_input_error([&] { read_compressed_ply(dir / "chunks.ply"); },
                       {"chunks.ply", "element 'chunk'", "1 chunks", "300 vertices need 2"});
}

TEST(FormatsCompressedPlyErrors, TruncatedBody) {
    ScratchDir dir;
    std::string bytes = random_file(300, true, 9, 8).bytes();
    bytes.resize(bytes.size() - 100);
    write_bytes(dir / "cut.ply", bytes);
    expect_input_error([&] { read_compressed_ply(dir / "cut.ply"); }, {"cut.ply", "element 'sh'", "truncated"});
}

TEST(FormatsCompressedPlyErrors, OverflowingCountIsRefused) {
    ScratchDir dir;
    std::string bytes = random_file(3, true, 0, 8).bytes();
    const std::string from = "element vertex 3\n";
    bytes.replace(bytes.find(from), from.size(), "element vertex 9223372036854775807\n");
    write_bytes(dir / "huge.ply", bytes);
    expect_input_error([&] { read_compressed_ply(dir / "huge.ply"); }, {"huge.ply", "element 'vertex'", "overflows"});
}

TEST(FormatsCompressedPlyErrors, MissingOrMistypedProperties) {
    ScratchDir dir;
    std::string bytes = random_file(3, true, 0, 9).bytes();
    bytes.replace(bytes.find("packed_rotation"), 15, "packed_rotatio_");
    write_bytes(dir / "norot.ply", bytes);
    expect_input_error([&] { read_compressed_ply(dir / "norot.ply"); },
                       {"norot.ply", "element 'vertex'", "missing required property packed_rotation"});

    bytes = random_file(3, true, 0, 9).bytes();
    bytes.replace(bytes.find("property uint packed_scale"), 26, "property int packed_scale");
    write_bytes(dir / "int.ply", bytes);
    expect_input_error([&] { read_compressed_ply(dir / "int.ply"); }, {"int.ply", "packed_scale must be uint"});

    bytes = random_file(3, true, 0, 9).bytes();
    bytes.replace(bytes.find("property float max_g\n"), 21, "");
    write_bytes(dir / "colour.ply", bytes);
    expect_input_error([&] { read_compressed_ply(dir / "colour.ply"); }, {"colour.ply", "not all of the colour range"});
}

TEST(FormatsCompressedPlyErrors, WrongShPropertyCount) {
    ScratchDir dir;
    CompressedFile file = random_file(3, true, 10, 10);
    write_bytes(dir / "sh10.ply", file.bytes());
    expect_input_error([&] { read_compressed_ply(dir / "sh10.ply"); }, {"sh10.ply", "element 'sh'", "10 properties"});
}

TEST(FormatsCompressedPlyErrors, AsciiIsRefused) {
    ScratchDir dir;
    write_bytes(dir / "ascii.ply", "ply\nformat ascii 1.0\nelement chunk 0\nproperty float min_x\nelement vertex 0\n"
                                   "property uint packed_position\nend_header\n");
    expect_input_error([&] { read_compressed_ply(dir / "ascii.ply"); }, {"ascii.ply", "must be binary"});
}

TEST(FormatsCompressedPlyErrors, NotAPly) {
    ScratchDir dir;
    write_bytes(dir / "junk.ply", "PK\x03\x04 definitely not a ply");
    expect_input_error([&] { read_compressed_ply(dir / "junk.ply"); }, {"junk.ply", "not a PLY"});
    expect_input_error([&] { read_scene(dir / "junk.ply"); }, {"junk.ply", "not a PLY"});
}

// The largest difference; an infinite expected value must have become the clamp of the same sign.
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

TEST(FormatsCompressedPlySharedData, SnowmikuMatchesSplatTransformsDecoding) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto folder = vksplat::test::shared_data_dir() / "formats";
    if (!std::filesystem::exists(folder / "snowmiku.compressed.ply"))
        GTEST_SKIP() << folder / "snowmiku.compressed.ply" << " not found";
    std::vector<std::string> notes;
    const GaussianCloud ours = read_scene(folder / "snowmiku.compressed.ply", &notes);
    const GaussianCloud expected = read_ply(folder / "snowmiku.compressed.decoded.ply");
    EXPECT_TRUE(notes.empty());
    ASSERT_EQ(ours.size(), 57694u);
    ASSERT_EQ(ours.sh_degree, 3);
    ASSERT_EQ(expected.size(), ours.size());
    const double position = max_difference(ours.positions, expected.positions);
    const double scale = max_difference(ours.log_scales, expected.log_scales);
    const double rotation = max_difference(ours.rotations, expected.rotations);
    const double opacity = max_difference(ours.opacity_logits, expected.opacity_logits, kMaxOpacityLogit);
    const double sh = max_difference(ours.sh, expected.sh);
    std::printf("snowmiku.compressed.ply max |ours - splat-transform|: position %.3g, log scale %.3g, "
                "rotation %.3g, opacity %.3g, sh %.3g\n",
                position, scale, rotation, opacity, sh);
    EXPECT_LE(position, 1e-6);
    EXPECT_LE(scale, 1e-6);
    EXPECT_LE(rotation, 1e-6);
    EXPECT_LE(opacity, 1e-5);
    EXPECT_LE(sh, 1e-6);
}

}  // namespace
}  // namespace vksplat::io::test
