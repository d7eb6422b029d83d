// The compressed-PLY writer: what it writes reads back within the layout's quantisation (each splat
// found again by its position, since the writer reorders them), its chunks are spatially compact
// (Morton order), and the header is the layout splat-transform and read_compressed_ply expect.
#include <gtest/gtest.h>

#include <cmath>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

// The largest minus the smallest of `values` at `axis` of each `stride`.
double extent(const std::vector<float>& values, size_t stride, size_t axis) {
    float low = INFINITY, high = -INFINITY;
    for (size_t i = axis; i < values.size(); i += stride) {
        low = std::min(low, values[i]);
        high = std::max(high, values[i]);
    }
    return double(high) - low;
}

// For each splat of `back`, the splat of `original` nearest to it; each must be found once.
std::vector<size_t> match_by_position(const GaussianCloud& original, const GaussianCloud& back) {
    std::vector<size_t> match(back.size());
    std::vector<int> found(original.size(), 0);
    for (size_t i = 0; i < back.size(); ++i) {
        double best = INFINITY;
        for (size_t j = 0; j < original.size(); ++j) {
            double d = 0;
            for (size_t a = 0; a < 3; ++a) d += std::pow(double(back.positions[i * 3 + a]) - original.positions[j * 3 + a], 2);
            if (d < best) best = d, match[i] = j;
        }
        ++found[match[i]];
    }
    for (size_t j = 0; j < original.size(); ++j) EXPECT_EQ(found[j], 1) << "original splat " << j;
    return match;
}

TEST(FormatsCompressedPlyWrite, RoundTripWithinQuantisation) {
    ScratchDir dir;
    for (int degree : {0, 1, 3}) {
        const GaussianCloud original = random_cloud(700, degree, 40 + degree);  // three chunks, the last partial
        const auto path = dir / ("scene" + std::to_string(degree) + ".compressed.ply");
        write_compressed_ply(original, path);
        ASSERT_TRUE(is_compressed_ply(path));
        const GaussianCloud back = read_compressed_ply(path);
        ASSERT_EQ(back.size(), original.size());
        ASSERT_EQ(back.sh_degree, degree);
        const std::vector<size_t> match = match_by_position(original, back);
        // Positions and log scales: half a step of their chunk's range, 11 bits for x and z, 10 for
        // y; every chunk's range is within the scene's. Colours: half of 1/255 of the chunk's range,
        // in f_dc units (over SH_C0). Opacity: half of 1/255 after the sigmoid. Rotations: each
        // smaller component to half of sqrt(2)/1023, the largest rebuilt from them (0.003 in all).
        // SH: half a bucket of 8/256 (the random values stay inside [-4, 4]). 1e-5 for float rounding.
        const size_t k = static_cast<size_t>(original.sh_coefficients());
        for (size_t i = 0; i < back.size(); ++i) {
            const size_t o = match[i];
            for (size_t a = 0; a < 3; ++a) {
                const double steps = a == 1 ? 1023 : 2047;
                EXPECT_NEAR(back.positions[i * 3 + a], original.positions[o * 3 + a],
                            extent(original.positions, 3, a) / steps / 2 + 1e-5);
                EXPECT_NEAR(back.log_scales[i * 3 + a], original.log_scales[o * 3 + a],
                            extent(original.log_scales, 3, a) / steps / 2 + 1e-5);
                EXPECT_NEAR(back.sh[i * k * 3 + a], original.sh[o * k * 3 + a],
                            extent(original.sh, k * 3, a) / 255 / 2 + 1e-5);
            }
            EXPECT_NEAR(sigmoid(back.opacity_logits[i]), sigmoid(original.opacity_logits[o]), 0.5 / 255 + 1e-6);
            double norm = 0, dot = 0;
            for (size_t a = 0; a < 4; ++a) norm += double(original.rotations[o * 4 + a]) * original.rotations[o * 4 + a];
            for (size_t a = 0; a < 4; ++a) dot += back.rotations[i * 4 + a] * original.rotations[o * 4 + a];
            for (size_t a = 0; a < 4; ++a)
                EXPECT_NEAR((dot < 0 ? -1 : 1) * back.rotations[i * 4 + a], original.rotations[o * 4 + a] / std::sqrt(norm),
                            0.003);
            for (size_t c = 3; c < k * 3; ++c)
                EXPECT_NEAR(back.sh[i * k * 3 + c], original.sh[o * k * 3 + c], 4.0 / 256 + 1e-5) << "Gaussian " << o;
        }
    }
}

TEST(FormatsCompressedPlyWrite, ChunksAreSpatiallyCompact) {
    ScratchDir dir;
    // 4096 splats spread over a cube: in file order each chunk of 256 would span nearly all of it;
    // in Morton order a chunk is about one of 16 cells of the curve, 1/16 of the volume, or two
    // neighbouring ones where the random counts put a chunk's end past a cell's (about 1/5 here).
    const GaussianCloud original = random_cloud(4096, 0, 9);
    write_compressed_ply(original, dir / "cube.compressed.ply");
    const GaussianCloud back = read_compressed_ply(dir / "cube.compressed.ply");
    double volume = 0;
    for (size_t c = 0; c < 16; ++c) {
        GaussianCloud chunk;
        chunk.positions.assign(back.positions.begin() + c * 256 * 3, back.positions.begin() + (c + 1) * 256 * 3);
        volume += extent(chunk.positions, 3, 0) * extent(chunk.positions, 3, 1) * extent(chunk.positions, 3, 2);
    }
    const double cube = extent(original.positions, 3, 0) * extent(original.positions, 3, 1) * extent(original.positions, 3, 2);
    EXPECT_LT(volume / 16, cube / 4) << "mean chunk box " << volume / 16 << " of a scene box " << cube;
}

TEST(FormatsCompressedPlyWrite, HeaderHasTheLayoutSplatTransformExpects) {
    ScratchDir dir;
    write_compressed_ply(random_cloud(300, 2, 5), dir / "scene.compressed.ply");
    const std::string bytes = read_bytes(dir / "scene.compressed.ply");
    const std::string header = bytes.substr(0, bytes.find("end_header\n"));
    // Three elements exactly (splat-transform refuses more): 18 float chunk ranges, 4 uint words, 24 SH bytes.
    EXPECT_NE(header.find("format binary_little_endian 1.0\n"), std::string::npos);
    EXPECT_NE(header.find("element chunk 2\nproperty float min_x\n"), std::string::npos);
    EXPECT_NE(header.find("property float max_b\nelement vertex 300\nproperty uint packed_position\n"), std::string::npos);
    EXPECT_NE(header.find("property uint packed_color\nelement sh 300\nproperty uchar f_rest_0\n"), std::string::npos);
    EXPECT_NE(header.find("property uchar f_rest_23\n"), std::string::npos);
    EXPECT_EQ(header.find("f_rest_24"), std::string::npos);
    EXPECT_EQ(bytes.size(), header.size() + 11 + 2 * 18 * 4 + 300 * 16 + 300 * 24);
}

TEST(FormatsCompressedPlyWrite, EmptyCloudAndNonFinitePositions) {
    ScratchDir dir;
    GaussianCloud empty;
    write_compressed_ply(empty, dir / "empty.compressed.ply");
    EXPECT_TRUE(read_compressed_ply(dir / "empty.compressed.ply").empty());
    GaussianCloud cloud = random_cloud(3, 0, 2);
    cloud.positions[4] = NAN;
    expect_input_error([&] { write_compressed_ply(cloud, dir / "nan.compressed.ply"); },
                       {"nan.compressed.ply", "Gaussian 1", "not finite"});
    EXPECT_FALSE(std::filesystem::exists(dir / "nan.compressed.ply"));
}

}  // namespace
}  // namespace vksplat::io::test
