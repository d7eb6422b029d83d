// SOG (PlayCanvas): what we write reads back within the format's quantisation, per attribute;
// the zip and the folder (meta.json) layouts hold the same scene; damaged files are refused with a
// message that names the file and the problem. (tests/io/splat_transform_test.sh checks both
// directions against splat-transform.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "io/io_test_helpers.hpp"
#include "io/webp_image.hpp"
#include "io/zip_archive.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io::test {
namespace {

namespace fs = std::filesystem;

// Values like a trained scene's, each attribute in its own range.
GaussianCloud scene_like_cloud(size_t count, int sh_degree, unsigned seed = 3) {
    GaussianCloud cloud = random_cloud(count, sh_degree, seed);
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> position(-20.0f, 20.0f), log_scale(-7.0f, 0.5f), dc(-1.5f, 1.5f),
        rest(-0.5f, 0.5f);
    for (float& v : cloud.positions) v = position(random);
    for (float& v : cloud.log_scales) v = log_scale(random);
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 0; i < cloud.size(); ++i)
        for (size_t k = 0; k < stride; ++k) cloud.sh[i * stride + k] = k < 3 ? dc(random) : rest(random);
    return cloud;
}

// For each Gaussian of `decoded`, the index of the one in `original` at the nearest position: the
// writer reorders them (Morton order). Fails unless that pairs them one to one.
std::vector<size_t> pair_by_position(const GaussianCloud& original, const GaussianCloud& decoded) {
    std::vector<size_t> pairs(decoded.size());
    for (size_t i = 0; i < decoded.size(); ++i) {
        double best = INFINITY;
        for (size_t j = 0; j < original.size(); ++j) {
            double distance = 0;
            for (size_t a = 0; a < 3; ++a)
                distance += std::pow(decoded.positions[i * 3 + a] - original.positions[j * 3 + a], 2);
            if (distance < best) best = distance, pairs[i] = j;
        }
    }
    EXPECT_EQ(std::set<size_t>(pairs.begin(), pairs.end()).size(), original.size());
    return pairs;
}

// Every decoded value is the entry nearest its original among all the values decoded (which hold
// every codebook entry in use): what a 256-entry codebook can do at best.
void expect_nearest_codebook_entries(const std::vector<float>& original, const std::vector<float>& decoded,
                                     const char* what) {
    const std::set<float> entries(decoded.begin(), decoded.end());
    EXPECT_LE(entries.size(), 256u) << what;
    for (size_t k = 0; k < original.size(); ++k) {
        auto above = entries.lower_bound(original[k]);
        double nearest = INFINITY;
        if (above != entries.end()) nearest = std::abs(*above - original[k]);
        if (above != entries.begin()) nearest = std::min(nearest, double(std::abs(*std::prev(above) - original[k])));
        ASSERT_LE(std::abs(decoded[k] - original[k]), nearest + 1e-7) << what << " value " << k;
    }
}

// `original` reordered as `decoded` is (pairs from pair_by_position): `per` values a Gaussian.
std::vector<float> reordered(const std::vector<float>& original, const std::vector<size_t>& pairs, size_t per) {
    std::vector<float> values(pairs.size() * per);
    for (size_t i = 0; i < pairs.size(); ++i)
        for (size_t k = 0; k < per; ++k) values[i * per + k] = original[pairs[i] * per + k];
    return values;
}

void expect_within_quantisation(const GaussianCloud& original, const GaussianCloud& decoded) {
    ASSERT_EQ(decoded.size(), original.size());
    ASSERT_EQ(decoded.sh_degree, original.sh_degree);
    const std::vector<size_t> pairs = pair_by_position(original, decoded);
    // Positions: 16 bits of v = sign(x) ln(|x| + 1) over each axis's range; half a step in v is
    // (|x| + 1) times that in x.
    for (size_t a = 0; a < 3; ++a) {
        double low = INFINITY, high = -INFINITY;
        for (size_t j = 0; j < original.size(); ++j) {
            const double x = original.positions[j * 3 + a];
            low = std::min(low, std::copysign(std::log1p(std::abs(x)), x));
            high = std::max(high, std::copysign(std::log1p(std::abs(x)), x));
        }
        const double half_step = (high - low) / 65535 / 2;
        for (size_t i = 0; i < decoded.size(); ++i) {
            const double x = original.positions[pairs[i] * 3 + a];
            EXPECT_LE(std::abs(decoded.positions[i * 3 + a] - x), (std::abs(x) + 1) * half_step * 1.001 + 1e-6)
                << "Gaussian " << pairs[i] << " axis " << a;
        }
    }
    // Rotations: the three smaller components of the unit quaternion in 8 bits each, times sqrt(2):
    // half a step is 2/255/sqrt(2)/2 = 0.00277; the largest, rebuilt from them, within 3x that.
    for (size_t i = 0; i < decoded.size(); ++i) {
        double q[4], length = 0;
        for (size_t k = 0; k < 4; ++k) length += std::pow(q[k] = original.rotations[pairs[i] * 4 + k], 2);
        size_t largest = 0;
        for (size_t k = 1; k < 4; ++k)
            if (std::abs(q[k]) > std::abs(q[largest])) largest = k;
        const double sign = q[largest] < 0 ? -1 : 1;
        for (size_t k = 0; k < 4; ++k) {
            const double error = std::abs(decoded.rotations[i * 4 + k] - sign * q[k] / std::sqrt(length));
            EXPECT_LE(error, k == largest ? 0.0084 : 0.00278) << "Gaussian " << pairs[i] << " component " << k;
        }
    }
    // Opacity after the sigmoid in a byte.
    for (size_t i = 0; i < decoded.size(); ++i)
        EXPECT_NEAR(sigmoid(decoded.opacity_logits[i]), sigmoid(original.opacity_logits[pairs[i]]), 0.5 / 255 + 1e-6);
    // Log scales, f_dc and (a palette entry per Gaussian, as these clouds are smaller than the
    // palette) the higher SH: each the nearest entry of its 256-entry codebook.
    expect_nearest_codebook_entries(reordered(original.log_scales, pairs, 3), decoded.log_scales, "log scale");
    const size_t stride = size_t(original.sh_coefficients()) * 3;
    const std::vector<float> sh = reordered(original.sh, pairs, stride);
    std::vector<float> dc, decoded_dc, rest, decoded_rest;
    for (size_t k = 0; k < sh.size(); ++k) {
        (k % stride < 3 ? dc : rest).push_back(sh[k]);
        (k % stride < 3 ? decoded_dc : decoded_rest).push_back(decoded.sh[k]);
    }
    expect_nearest_codebook_entries(dc, decoded_dc, "f_dc");
    expect_nearest_codebook_entries(rest, decoded_rest, "higher SH");
}

TEST(SogFormat, RoundTripsWithinItsQuantisation) {
    ScratchDir dir;
    for (const int degree : {0, 1, 3}) {
        const GaussianCloud cloud = scene_like_cloud(700, degree);
        const fs::path path = dir / ("degree" + std::to_string(degree) + ".sog");
        write_sog(cloud, path);
        EXPECT_EQ(read_bytes(path).substr(0, 4), std::string("PK\x03\x04", 4));
        SCOPED_TRACE("SH degree " + std::to_string(degree));
        expect_within_quantisation(cloud, read_sog(path));
    }
}

TEST(SogFormat, CodebooksAreExactWhenTheValuesAreFew) {
    ScratchDir dir;
    GaussianCloud cloud = scene_like_cloud(50, 2);
    for (size_t i = 0; i < cloud.log_scales.size(); ++i) cloud.log_scales[i] = -float(i % 7);  // 7 values
    write_sog(cloud, dir / "few.sog");
    const GaussianCloud decoded = read_sog(dir / "few.sog");
    const auto pairs = pair_by_position(cloud, decoded);
    EXPECT_EQ(decoded.log_scales, reordered(cloud.log_scales, pairs, 3));
    // 50 x 3 f_dc values: fewer than the codebook's 256 entries, so each is an entry.
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 0; i < decoded.size(); ++i)
        for (size_t c = 0; c < 3; ++c) EXPECT_EQ(decoded.sh[i * stride + c], cloud.sh[pairs[i] * stride + c]);
}

// Beyond the palette's 4096 entries k-means picks them; a scene whose higher SH take 400 values
// keeps each exactly (entry indices beyond 255 need the label's second byte).
TEST(SogFormat, PaletteOfMoreSplatsThanEntriesKeepsRepeatedShExactly) {
    ScratchDir dir;
    GaussianCloud cloud = scene_like_cloud(4500, 1);
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 400; i < cloud.size(); ++i)
        std::copy_n(&cloud.sh[(i % 400) * stride + 3], stride - 3, &cloud.sh[i * stride + 3]);
    write_sog(cloud, dir / "palette.sog");
    const GaussianCloud decoded = read_sog(dir / "palette.sog");
    const auto pairs = pair_by_position(cloud, decoded);
    std::vector<float> rest, decoded_rest;
    for (size_t i = 0; i < decoded.size(); ++i)
        for (size_t k = 3; k < stride; ++k) {
            rest.push_back(cloud.sh[pairs[i] * stride + k]);
            decoded_rest.push_back(decoded.sh[i * stride + k]);
        }
    expect_nearest_codebook_entries(rest, decoded_rest, "higher SH");
}

TEST(SogFormat, FolderLayoutHoldsTheSameSceneAsTheZip) {
    ScratchDir dir;
    const GaussianCloud cloud = scene_like_cloud(300, 3);
    write_scene(cloud, dir / "scene.sog");
    fs::create_directories(dir / "folder");
    write_scene(cloud, dir / "folder" / "meta.json");
    for (const char* name : {"meta.json", "means_l.webp", "means_u.webp", "quats.webp", "scales.webp", "sh0.webp",
                             "shN_centroids.webp", "shN_labels.webp"})
        EXPECT_TRUE(fs::exists(dir / "folder" / name)) << name;
    EXPECT_EQ(scene_format_of(dir / "folder" / "meta.json"), "sog");
    EXPECT_EQ(scene_format_of(dir / "scene.sog"), "sog");
    const GaussianCloud from_zip = read_scene(dir / "scene.sog");
    const GaussianCloud from_folder = read_scene(dir / "folder" / "meta.json");
    EXPECT_EQ(from_folder.positions, from_zip.positions);
    EXPECT_EQ(from_folder.rotations, from_zip.rotations);
    EXPECT_EQ(from_folder.sh, from_zip.sh);
    // The same scene makes the same bytes: k-means is seeded, the zip dated 1980.
    write_scene(cloud, dir / "again.sog");
    EXPECT_EQ(read_bytes(dir / "again.sog"), read_bytes(dir / "scene.sog"));
}

TEST(SogFormat, FolderTexturesAreNotOverwrittenWithoutAsking) {
    ScratchDir dir;
    write_bytes(dir / "quats.webp", "the user's picture");
    const GaussianCloud cloud = scene_like_cloud(20, 0);
    expect_input_error([&] { check_scene_writable(dir / "meta.json"); }, {"quats.webp", "exists"});
    expect_input_error([&] { write_scene(cloud, dir / "meta.json"); }, {"quats.webp", "exists"});
    EXPECT_FALSE(fs::exists(dir / "meta.json"));
    EXPECT_FALSE(fs::exists(dir / "means_l.webp"));
    EXPECT_EQ(read_bytes(dir / "quats.webp"), "the user's picture");
    write_scene(cloud, dir / "meta.json", WriteMode::overwrite);
    EXPECT_EQ(read_sog(dir / "meta.json").size(), 20u);
}

TEST(SogFormat, EmptySceneRoundTrips) {
    ScratchDir dir;
    GaussianCloud empty;
    empty.sh_degree = 3;
    write_sog(empty, dir / "empty.sog");
    const GaussianCloud decoded = read_sog(dir / "empty.sog");
    EXPECT_EQ(decoded.size(), 0u);
    EXPECT_EQ(decoded.sh_degree, 3);
}

TEST(SogFormat, UndefinedValuesAreRefusedByGaussian) {
    ScratchDir dir;
    GaussianCloud cloud = scene_like_cloud(10, 1);
    cloud.positions[3 * 4 + 1] = NAN;
    expect_input_error([&] { write_sog(cloud, dir / "nan.sog"); }, {"nan.sog", "Gaussian 4", "position"});
    cloud = scene_like_cloud(10, 1);
    std::fill_n(&cloud.rotations[4 * 7], 4, 0.0f);
    expect_input_error([&] { write_sog(cloud, dir / "zero.sog"); }, {"zero.sog", "Gaussian 7", "length 0"});
    EXPECT_FALSE(fs::exists(dir / "nan.sog"));
}

// A SOG folder written from a small scene, for the damage tests to break.
class DamagedSog : public ::testing::Test {
protected:
    void SetUp() override { write_sog(scene_like_cloud(40, 1), dir_ / "meta.json"); }
    nlohmann::json meta() const { return nlohmann::json::parse(read_bytes(dir_ / "meta.json")); }
    void set_meta(const nlohmann::json& meta) const { write_bytes(dir_ / "meta.json", meta.dump()); }
    void expect_refused(const std::vector<std::string>& parts) const {
        expect_input_error([&] { read_sog(dir_ / "meta.json"); }, parts);
    }
    void replace_texture(const std::string& name, int width, int height, uint8_t alpha = 255) const {
        detail::RgbaImage image{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, alpha)};
        write_bytes(dir_ / name, detail::encode_lossless_webp(image, name));
    }
    ScratchDir dir_;
};

TEST_F(DamagedSog, MetaJsonThatIsNotJsonIsRefused) {
    write_bytes(dir_ / "meta.json", "{\"version\": 2, \"count\": ");
    expect_refused({"meta.json", "malformed JSON"});
}

TEST_F(DamagedSog, MetaJsonWithoutAKeyIsRefusedByName) {
    const nlohmann::json original = meta();
    nlohmann::json broken = original;
    broken.erase("count");
    set_meta(broken);
    expect_refused({"meta.json", "missing key 'count'"});
    broken = original;
    broken["scales"]["codebook"] = "many";
    set_meta(broken);
    expect_refused({"meta.json", "scales.codebook"});
}

TEST_F(DamagedSog, OtherVersionsAreRefused) {
    nlohmann::json broken = meta();
    broken.erase("version");
    set_meta(broken);
    expect_refused({"meta.json", "'version'", "version 2"});
    broken["version"] = 3;
    set_meta(broken);
    expect_refused({"meta.json", "SOG version 3"});
}

TEST_F(DamagedSog, TextureOutsideTheFolderIsRefused) {
    nlohmann::json broken = meta();
    broken["quats"]["files"][0] = "../quats.webp";
    set_meta(broken);
    expect_refused({"meta.json", "\"../quats.webp\"", "file name"});
}

TEST_F(DamagedSog, MissingTextureIsRefusedByName) {
    fs::remove(dir_ / "quats.webp");
    expect_refused({"quats.webp", "missing"});
}

TEST_F(DamagedSog, MissingTextureInTheZipIsRefusedByName) {
    std::vector<std::pair<std::string, std::string>> files{{"meta.json", read_bytes(dir_ / "meta.json")}};
    for (const char* name : {"means_l.webp", "means_u.webp", "quats.webp", "sh0.webp", "shN_centroids.webp",
                             "shN_labels.webp"})
        files.emplace_back(name, read_bytes(dir_ / name));
    write_bytes(dir_ / "no_scales.sog", zip::stored_archive(files, "no_scales.sog"));
    expect_input_error([&] { read_sog(dir_ / "no_scales.sog"); }, {"no_scales.sog", "scales.webp", "missing"});
}

TEST_F(DamagedSog, TextureOfTheWrongSizeIsRefused) {
    replace_texture("scales.webp", 4, 4);  // the others are 8x8 for 40 splats
    expect_refused({"scales.webp", "wrong texture size", "4x4", "means_l.webp is 8x8"});
}

TEST_F(DamagedSog, TexturesTooSmallForTheCountAreRefused) {
    nlohmann::json broken = meta();
    broken["count"] = 65;  // 8x8 textures hold 64
    set_meta(broken);
    expect_refused({"means_l.webp", "wrong texture size", "fewer than the 65"});
}

TEST_F(DamagedSog, PaletteOfTheWrongWidthIsRefused) {
    replace_texture("shN_centroids.webp", 64 * 8, 1);  // degree 1 takes 3 coefficients an entry, not 8
    expect_refused({"shN_centroids.webp", "wrong texture size", "512 texels wide"});
}

TEST_F(DamagedSog, TextureThatIsNotWebpIsRefused) {
    write_bytes(dir_ / "sh0.webp", "RIFF....not a picture");
    expect_refused({"sh0.webp", "not a WebP image"});
}

TEST_F(DamagedSog, IndexBeyondItsCodebookIsRefused) {
    nlohmann::json broken = meta();
    broken["sh0"]["codebook"] = {0.5, 0.25};
    set_meta(broken);
    expect_refused({"sh0.webp", "of a codebook of 2"});
}

TEST_F(DamagedSog, QuaternionWithoutItsTagIsRefused) {
    replace_texture("quats.webp", 8, 8, 17);
    expect_refused({"quats.webp", "alpha 17"});
}

TEST(SogFormat, FileThatIsNeitherZipNorJsonIsRefused) {
    ScratchDir dir;
    write_bytes(dir / "scene.sog", "ply\nformat binary_little_endian 1.0\n");
    expect_input_error([&] { read_scene(dir / "scene.sog"); }, {"scene.sog", "not a SOG scene"});
    write_bytes(dir / "empty.sog", std::string("PK\x05\x06", 4) + std::string(18, '\0'));
    expect_input_error([&] { read_scene(dir / "empty.sog"); }, {"empty.sog", "meta.json", "missing"});
}

}  // namespace
}  // namespace vksplat::io::test
