// ply_bytes() is the exact size of the file the standard INRIA writer produces.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/test_data.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

GaussianCloud zero_cloud(size_t n, int degree) {
    GaussianCloud cloud;
    cloud.sh_degree = degree;
    cloud.resize(n);
    return cloud;
}

TEST(PlyBytes, HandCountedHeaderForOneDegreeZeroGaussian) {
    // "ply\n" 4 + "format binary_little_endian 1.0\n" 32 + "element vertex 1\n" 17 + "end_header\n" 11,
    // 17 "property float <name>\n" lines: 16 bytes each plus the names
    // (x y z nx ny nz f_dc_0..2 opacity scale_0..2 rot_0..3: 3 + 6 + 18 + 7 + 21 + 20 = 75 characters).
    const size_t header = 4 + 32 + 17 + 11 + 17 * 16 + 75;
    EXPECT_EQ(zero_cloud(1, 0).ply_bytes(), header + 17 * 4);
}

TEST(PlyBytes, MatchesTheSizeOfTheWrittenFile) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "vksplat_ply_bytes_test";
    std::filesystem::create_directories(dir);
    for (int degree = 0; degree <= 3; ++degree)
        for (size_t n : {0u, 1u, 9u, 10u, 1234u}) {
            const GaussianCloud cloud = zero_cloud(n, degree);
            const std::filesystem::path path = dir / ("cloud_" + std::to_string(degree) + "_" + std::to_string(n) + ".ply");
            std::filesystem::remove(path);
            io::write_ply(cloud, path);
            EXPECT_EQ(cloud.ply_bytes(), std::filesystem::file_size(path)) << "degree " << degree << ", " << n << " Gaussians";
        }
    std::filesystem::remove_all(dir);
}

TEST(PlyBytes, MatchesTheTrainersLegoFile) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    // lego/point_cloud.ply was written by the INRIA trainer: 245,000 Gaussians of degree 3.
    EXPECT_EQ(zero_cloud(245000, 3).ply_bytes(),
              std::filesystem::file_size(test::shared_data_dir() / "lego" / "point_cloud.ply"));
}

}  // namespace
}  // namespace vksplat
