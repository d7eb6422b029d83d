// Region maps: compaction, mask stacks (smaller wins), and the file forms they are read from.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "vksplat/cluster/region_map.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::cluster {
namespace {

namespace fs = std::filesystem;

class RegionMapFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("vksplat_region_map_" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

TEST(RegionMap, CompactsIdsInOrderOfAppearance) {
    RegionMap map{3, 2, {7, 7, -5, 300, 7, 2}};
    compact_ids(map);
    EXPECT_EQ(map.labels, (std::vector<int32_t>{0, 0, kNoRegion, 1, 0, 2}));
    EXPECT_EQ(map.region_count(), 3u);
    EXPECT_EQ(map.labelled_pixels(), 5u);
}

TEST(RegionMap, SmallerMasksWinWhereTheyOverlap) {
    // A whole (all 4 pixels but one), a part inside it, and an empty mask.
    const std::vector<std::vector<uint8_t>> masks{{0, 1, 0, 0}, {1, 1, 1, 0}, {0, 0, 0, 0}};
    const RegionMap map = combine_masks(masks, 2, 2);
    EXPECT_EQ(map.labels, (std::vector<int32_t>{1, 0, 1, kNoRegion}));
    EXPECT_THROW(combine_masks({{1, 0}}, 2, 2), InputError);
}

TEST_F(RegionMapFiles, ReadsInt32MapsMaskStacksAndLabelImages) {
    const std::vector<int32_t> ids{5, 5, -1, 9, 9, 9};
    io::write_npy(dir / "map.npy", ids.data(), {2, 3});
    const RegionMap map = read_region_map(dir / "map.npy");
    EXPECT_EQ(map.width, 3);
    EXPECT_EQ(map.height, 2);
    EXPECT_EQ(map.labels, (std::vector<int32_t>{0, 0, kNoRegion, 1, 1, 1}));

    const std::vector<uint8_t> masks{1, 1, 1, 1, /* second mask */ 0, 1, 0, 0};  // [2, 2, 2]
    io::write_npy(dir / "masks.npy", masks.data(), {2, 2, 2});
    EXPECT_EQ(read_region_map(dir / "masks.npy").labels, (std::vector<int32_t>{0, 1, 0, 0}));

    const std::vector<float> labels{0.0f, 40000.0f / 65535, 3.0f / 65535, 40000.0f / 65535};
    io::write_png_gray16(dir / "labels.png", 2, 2, labels.data());
    EXPECT_EQ(read_region_map(dir / "labels.png").labels, (std::vector<int32_t>{kNoRegion, 0, 1, 0}));
}

TEST_F(RegionMapFiles, RejectsOtherFormsNamingTheFile) {
    const std::vector<float> values{1, 2};
    io::write_npy(dir / "floats.npy", values.data(), {1, 2});
    try {
        read_region_map(dir / "floats.npy");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("floats.npy"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_region_map(dir / "missing.npy"), InputError);
    const std::vector<float> colour(2 * 2 * 3, 0.5f);
    io::write_png_rgb(dir / "colour.png", 2, 2, colour.data(), 8);
    EXPECT_THROW(read_region_map(dir / "colour.png"), InputError);
}

TEST_F(RegionMapFiles, WritesWhatItReads) {
    const RegionMap map{2, 1, {0, kNoRegion}};
    write_region_map(dir / "out.npy", map);
    EXPECT_EQ(read_region_map(dir / "out.npy").labels, map.labels);
    EXPECT_THROW(write_region_map(dir / "out.npy", map), InputError);  // never overwritten unasked
}

}  // namespace
}  // namespace vksplat::cluster
