// find_image(): camera names with or without the photo's extension.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io::test {
namespace {

TEST(FindImage, ExactNameExtensionsAndStem) {
    ScratchDir dir;
    for (const char* name : {"a.png", "b.jpg", "c.JPG", "d.jpeg", "e.webp", "f.png", "f.jpg"})
        write_bytes(dir / name, "x");
    std::filesystem::create_directories(dir / "train");
    write_bytes(dir / "train" / "r_0.png", "x");

    EXPECT_EQ(find_image(dir.path(), "a.png"), dir / "a.png");
    EXPECT_EQ(find_image(dir.path(), "a"), dir / "a.png");
    EXPECT_EQ(find_image(dir.path(), "b"), dir / "b.jpg");
    EXPECT_EQ(find_image(dir.path(), "c"), dir / "c.JPG");
    EXPECT_EQ(find_image(dir.path(), "d"), dir / "d.jpeg");
    EXPECT_EQ(find_image(dir.path(), "e.png"), dir / "e.webp");  // by stem
    EXPECT_EQ(find_image(dir.path(), "f"), dir / "f.png");       // extensions are tried in order
    EXPECT_EQ(find_image(dir.path(), "./train/r_0"), dir / "./train/r_0.png");
}

TEST(FindImage, ErrorsListWhereItLooked) {
    ScratchDir dir;
    write_bytes(dir / "f.png", "x");
    write_bytes(dir / "f.jpg", "x");
    expect_input_error([&] { find_image(dir.path(), "zzz"); }, {dir.path().string(), "no image for camera 'zzz'",
                                                                ".png, .jpg, .jpeg, .JPG, .PNG", "stem 'zzz'"});
    expect_input_error([&] { find_image(dir.path(), "f.tif"); }, {"'f.tif'", "several files: f.jpg f.png"});
}

}  // namespace
}  // namespace vksplat::io::test
