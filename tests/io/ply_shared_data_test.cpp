// The real scenes in ../shared/data: counts, degree, notes, a value decoded by hand, and speed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>

#include "io/io_test_helpers.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

TEST(PlySharedData, LegoLoadsQuicklyWithDegreeThreeAndANoteOnNormals) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto path = vksplat::test::shared_data_dir() / "lego" / "point_cloud.ply";
    std::vector<std::string> notes;
    const auto start = std::chrono::steady_clock::now();
    const GaussianCloud cloud = read_ply(path, &notes);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("lego_read_seconds", std::to_string(seconds));
    // Well under a second on an idle machine; the bound leaves room for a busy one.
    EXPECT_LT(seconds, 3.0);
    EXPECT_EQ(cloud.size(), 245000u);
    EXPECT_EQ(cloud.sh_degree, 3);
    EXPECT_NO_THROW(cloud.check_consistent());
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("nx"), std::string::npos) << notes[0];

    // The last vertex, decoded by hand: 62 little-endian floats at the end of the file.
    const std::string bytes = read_bytes(path);
    float row[62];
    std::memcpy(row, bytes.data() + bytes.size() - sizeof row, sizeof row);
    const size_t last = cloud.size() - 1;
    EXPECT_EQ(cloud.positions[last * 3 + 2], row[2]);
    EXPECT_EQ(cloud.sh[last * 48 + 0], row[6]);                // f_dc_0
    EXPECT_EQ(cloud.sh[last * 48 + 1 * 3 + 1], row[9 + 15]);   // f_rest_15: green, coefficient 1
    EXPECT_EQ(cloud.sh[last * 48 + 15 * 3 + 2], row[9 + 44]);  // f_rest_44: blue, coefficient 15
    EXPECT_EQ(cloud.opacity_logits[last], row[54]);
    EXPECT_EQ(cloud.log_scales[last * 3 + 1], row[56]);
    EXPECT_EQ(cloud.rotations[last * 4 + 3], row[61]);
}

TEST(PlySharedData, SnowmikuHasItsGaussians) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const GaussianCloud cloud = read_ply(vksplat::test::shared_data_dir() / "snowmiku" / "point_cloud.ply");
    EXPECT_EQ(cloud.size(), 57694u);
    EXPECT_EQ(cloud.sh_degree, 3);
}

// splat-transform writes another property order (x y z scale f_dc opacity rot f_rest).
TEST(PlySharedData, SplatTransformOrderDecodes) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto path = vksplat::test::shared_data_dir() / "formats" / "snowmiku.spz.decoded.ply";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
    std::vector<std::string> notes;
    const GaussianCloud cloud = read_ply(path, &notes);
    EXPECT_EQ(cloud.size(), 57694u);
    EXPECT_EQ(cloud.sh_degree, 3);
    EXPECT_TRUE(notes.empty());
}

}  // namespace
}  // namespace vksplat::io::test
