// SH precision: coefficients rounded to fewer bits of SPZ's byte, read back by the SPZ reader as
// they were, in a smaller file.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/prune/sh_precision.hpp"

namespace vksplat::test {
namespace {

TEST(ShPrecision, RoundsSpzBytesToTheNearestMultipleOfTheBucket) {
    GaussianCloud cloud = random_scene(91, 1, 3);
    const size_t stride = 48;
    for (size_t f = 0; f < stride; ++f) cloud.sh[f] = 0.3f;  // byte round(128 * 0.3 + 128) = 166
    cloud.sh[3 * 2 + 1] = -0.99f;                              // degree 1: byte 1
    cloud.sh[3 * 9] = 2.0f;                                    // beyond the byte: 255
    const GaussianCloud rounded = prune::with_sh_precision(cloud, {6, 4});
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(rounded.sh[c], 0.3f) << "the DC term is not SPZ's SH byte";
    // Degree 1 keeps 6 bits (buckets of 4): 166 -> 168; degrees 2 and 3 keep 4 (buckets of 16): 166 -> 160.
    EXPECT_EQ(rounded.sh[3 * 1], (168.0f - 128.0f) / 128.0f);
    EXPECT_EQ(rounded.sh[3 * 3 + 2], (168.0f - 128.0f) / 128.0f);
    EXPECT_EQ(rounded.sh[3 * 2 + 1], -1.0f) << "byte 1 rounds down to 0";
    EXPECT_EQ(rounded.sh[3 * 4], (160.0f - 128.0f) / 128.0f);
    EXPECT_EQ(rounded.sh[3 * 15 + 2], (160.0f - 128.0f) / 128.0f);
    EXPECT_EQ(rounded.sh[3 * 9], 127.0f / 128.0f) << "255 is the byte's end: 256 clamps to it";
    EXPECT_EQ(prune::with_sh_precision(cloud, {8, 8}).sh[3 * 4], (166.0f - 128.0f) / 128.0f);
}

TEST(ShPrecision, AnSpzFileHoldsTheRoundedValuesExactlyInFewerBytes) {
    const std::filesystem::path dir = fresh_test_dir("sh_precision");
    const GaussianCloud cloud = random_scene(92, 4000, 3);
    const GaussianCloud full = prune::with_sh_precision(cloud, {8, 8});
    const GaussianCloud rounded = prune::with_sh_precision(cloud, {7, 5});
    io::write_spz(full, dir / "full.spz");
    io::write_spz(rounded, dir / "rounded.spz");
    const GaussianCloud back = io::read_spz(dir / "rounded.spz");
    ASSERT_EQ(back.sh.size(), rounded.sh.size());
    for (size_t f = 0; f < back.sh.size(); ++f) {
        if (f % 48 >= 3) {
            ASSERT_EQ(back.sh[f], rounded.sh[f]) << "SH float " << f;
        }
    }
    EXPECT_LT(std::filesystem::file_size(dir / "rounded.spz"),
              std::filesystem::file_size(dir / "full.spz") * 9 / 10);
    std::filesystem::remove_all(dir);
}

TEST(ShPrecision, BitsOutsideOneToEightAreRefused) {
    const GaussianCloud cloud = random_scene(93, 2, 3);
    EXPECT_THROW(prune::with_sh_precision(cloud, {0, 6}), InputError);
    EXPECT_THROW(prune::with_sh_precision(cloud, {8, 9}), InputError);
    try {
        prune::check_sh_precision({7, 12});
        FAIL() << "12 bits were accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--sh-bits 7,12"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vksplat::test
