// The Gaussians training starts from: points with a NaN coordinate are dropped when the points are
// read, before the neighbour search that sizes the others, so those come out as without them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/sfm_points.hpp"
#include "vksplat/train/initialize.hpp"

namespace vksplat::test {
namespace {

// A binary points3D.ply (x, y, z float; red, green, blue uchar), as the reference writes it.
void write_points_ply(const std::filesystem::path& path, const std::vector<float>& positions) {
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << positions.size() / 3
        << "\nproperty float x\nproperty float y\nproperty float z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        out.write(reinterpret_cast<const char*>(&positions[3 * i]), 3 * sizeof(float));
        const unsigned char rgb[3] = {10, 200, 90};
        out.write(reinterpret_cast<const char*>(rgb), 3);
    }
}

TEST(InitialCloud, NanPointsAreDroppedBeforeTheNeighbourSearch) {
    const auto dir = fresh_test_dir("initialize");
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    std::vector<float> clean(3 * 40);
    for (float& v : clean) v = coordinate(rng);
    // Three NaN points among them, one with every coordinate NaN.
    std::vector<float> with_nan = clean;
    const float nan = std::nanf("");
    for (const size_t at : {5u, 17u, 30u}) with_nan.insert(with_nan.begin() + 3 * at, {nan, at == 17 ? nan : 0.1f, nan});

    std::filesystem::create_directories(dir / "clean");
    std::filesystem::create_directories(dir / "nan");
    write_points_ply(dir / "clean" / "points3D.ply", clean);
    write_points_ply(dir / "nan" / "points3D.ply", with_nan);
    std::vector<std::string> warnings;
    const io::SfmPoints read = io::read_sfm_points(dir / "nan", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("points3D.ply: dropped 3 of 43 points with a non-finite coordinate"), std::string::npos)
        << warnings[0];

    const GaussianCloud expected = train::initial_cloud(io::read_sfm_points(dir / "clean"), 0);
    const GaussianCloud got = train::initial_cloud(read, 0);
    EXPECT_EQ(got.positions, expected.positions);
    EXPECT_EQ(got.log_scales, expected.log_scales);
    EXPECT_EQ(got.sh, expected.sh);
    std::filesystem::remove_all(dir);
}

TEST(InitialCloud, RefusesANonFinitePoint) {
    io::SfmPoints points;
    points.positions = {0, 0, 0, 1, std::numeric_limits<float>::infinity(), 0};
    points.colors = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    try {
        train::initial_cloud(points, 0);
        FAIL() << "an infinite point was sized among the others";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("point 1: has a non-finite coordinate"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vksplat::test
