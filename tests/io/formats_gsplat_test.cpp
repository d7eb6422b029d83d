// gsplat checkpoints: archives built here the way torch.save builds them (a zip of a protocol-2
// pickle and raw storages) decode to the tensors they describe, whatever their strides, offsets,
// dtypes and compression; the fixture saved by PyTorch equals the PLY it came from; malformed
// archives and pickles are refused with a useful message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "io/io_test_helpers.hpp"
#include "io/torch_save_writer.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

uint16_t half_of(float value) {
    // Exact for the values used here (small dyadic rationals).
    uint32_t bits;
    std::memcpy(&bits, &value, 4);
    const uint32_t sign = (bits >> 16) & 0x8000u;
    const int exponent = static_cast<int>((bits >> 23) & 0xff) - 127 + 15;
    if ((bits & 0x7fffffffu) == 0) return static_cast<uint16_t>(sign);
    return static_cast<uint16_t>(sign | (exponent << 10) | ((bits >> 13) & 0x3ffu));
}

constexpr int64_t kN = 5;
constexpr int64_t kK = 3;  // SH degree 1

// The cloud the archive below holds.
GaussianCloud expected_small_cloud() {
    GaussianCloud cloud = random_cloud(kN, 1, 21);
    const float opacities[kN] = {-1.5f, 0.25f, 2.0f, -0.125f, 6.5f};  // exact in float16
    for (int64_t i = 0; i < kN; ++i) cloud.opacity_logits[i] = opacities[i];
    return cloud;
}

struct Archive {
    std::vector<ZipInput> entries;
    Pickle pickle;
};

// A checkpoint of expected_small_cloud() whose tensors use every layout trick torch can produce.
Archive small_archive(bool include_quats = true, std::vector<int64_t> quat_sizes = {kN, 4}) {
    const GaussianCloud cloud = expected_small_cloud();
    Archive archive;
    // Storage 0 (float32): two floats of padding, the means, then the quaternions (shared storage).
    std::string s0;
    append<float>(s0, 99.0f);
    append<float>(s0, 98.0f);
    for (float v : cloud.positions) append(s0, v);
    for (float v : cloud.rotations) append(s0, v);
    // Storage 1 (float32): the scales transposed, [3][N], viewed as [N, 3] with strides (1, N).
    std::string s1;
    for (int64_t a = 0; a < 3; ++a)
        for (int64_t i = 0; i < kN; ++i) append(s1, cloud.log_scales[i * 3 + a]);
    // Storage 2 (float16): opacities.
    std::string s2;
    for (float v : cloud.opacity_logits) append(s2, half_of(v));
    // Storage 3 (float64): sh0.
    std::string s3;
    for (int64_t i = 0; i < kN; ++i)
        for (int64_t a = 0; a < 3; ++a) append<double>(s3, cloud.sh[i * 12 + a]);
    // Storage 4 (float32, deflated): shN channel-major [N][3][K], viewed as [N, K, 3].
    std::string s4;
    for (int64_t i = 0; i < kN; ++i)
        for (int64_t a = 0; a < 3; ++a)
            for (int64_t k = 1; k <= kK; ++k) append(s4, cloud.sh[i * 12 + k * 3 + a]);

    Pickle& p = archive.pickle;
    p.op('}').put(0).mark().text("step").integer(29999).text("splats").ordered_dict().put(1).mark();
    p.text("means").tensor("FloatStorage", "0", 2 + kN * 7, 2, {kN, 3}, {3, 1}, 2);
    if (include_quats) p.text("quats").tensor("FloatStorage", "0", 2 + kN * 7, 2 + kN * 3, quat_sizes, {4, 1}, 2, true);
    p.text("scales").tensor("FloatStorage", "1", kN * 3, 0, {kN, 3}, {1, kN}, 3);
    p.text("opacities").tensor("HalfStorage", "2", kN, 0, {kN}, {1}, 4);
    p.text("sh0").tensor("DoubleStorage", "3", kN * 3, 0, {kN, 1, 3}, {3, 3, 1}, 5);
    p.text("shN").tensor("FloatStorage", "4", kN * 3 * kK, 0, {kN, kK, 3}, {3 * kK, 1, kK}, 6);
    p.text("features").integer(7);
    p.op('u');
    // The state an OrderedDict state_dict carries (its _metadata), applied by BUILD.
    p.op('}').mark().text("_metadata").ordered_dict().op('u').op('b');
    p.op('u');
    archive.entries = {{"ckpt/data/0", s0}, {"ckpt/data/1", s1}, {"ckpt/data/2", s2},
                       {"ckpt/data/3", s3}, {"ckpt/data/4", s4, true}, {"ckpt/version", "3\n"},
                       {"ckpt/byteorder", "little"}};
    return archive;
}

std::string archive_bytes(Archive archive) {
    archive.entries.insert(archive.entries.begin(), {"ckpt/data.pkl", archive.pickle.finish()});
    return zip_of(archive.entries);
}

TEST(FormatsGsplat, HandBuiltCheckpointDecodesWithItsStridesOffsetsAndDtypes) {
    ScratchDir dir;
    write_bytes(dir / "ckpt.pt", archive_bytes(small_archive()));
    std::vector<std::string> notes;
    const GaussianCloud cloud = read_gsplat_checkpoint(dir / "ckpt.pt", &notes);
    EXPECT_NO_THROW(cloud.check_consistent());
    const GaussianCloud expected = expected_small_cloud();
    // float16 and float64 are exact for these values: everything comes back bit for bit.
    expect_same_cloud(cloud, expected);
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("features"), std::string::npos) << notes[0];
    EXPECT_NE(notes[1].find("step 29999"), std::string::npos) << notes[1];
    // And through read_scene, by extension and by name.
    expect_same_cloud(read_scene(dir / "ckpt.pt"), expected);
    std::filesystem::copy_file(dir / "ckpt.pt", dir / "ckpt.bin");
    expect_same_cloud(read_scene(dir / "ckpt.bin", nullptr, "gsplat-pt"), expected);
}

TEST(FormatsGsplat, TensorsAtTheTopLevelAreAccepted) {
    ScratchDir dir;
    Archive archive = small_archive();
    // Replace the pickle by a plain dict of the tensors, without "splats".
    Pickle p;
    p.op('}').put(0).mark();
    p.text("means").tensor("FloatStorage", "0", 2 + kN * 7, 2, {kN, 3}, {3, 1}, 2);
    p.text("quats").tensor("FloatStorage", "0", 2 + kN * 7, 2 + kN * 3, {kN, 4}, {4, 1}, 2, true);
    p.text("scales").tensor("FloatStorage", "1", kN * 3, 0, {kN, 3}, {1, kN}, 3);
    p.text("opacities").tensor("HalfStorage", "2", kN, 0, {kN, 1}, {1, 1}, 4);
    p.text("sh0").tensor("DoubleStorage", "3", kN * 3, 0, {kN, 3}, {3, 1}, 5);
    p.op('u');
    archive.pickle = p;
    write_bytes(dir / "flat.pt", archive_bytes(archive));
    const GaussianCloud cloud = read_gsplat_checkpoint(dir / "flat.pt");
    const GaussianCloud expected = expected_small_cloud().with_sh_degree(0);  // no shN: degree 0
    expect_same_cloud(cloud, expected);
}

TEST(FormatsGsplatErrors, NotAZipArchive) {
    ScratchDir dir;
    write_bytes(dir / "text.pt", std::string(200, 'x'));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "text.pt"); }, {"text.pt", "not a zip archive"});
    write_bytes(dir / "tiny.pt", "PK");
    expect_input_error([&] { read_gsplat_checkpoint(dir / "tiny.pt"); }, {"tiny.pt", "too short"});
}

TEST(FormatsGsplatErrors, TruncatedArchive) {
    ScratchDir dir;
    const std::string bytes = archive_bytes(small_archive());
    write_bytes(dir / "half.pt", bytes.substr(0, bytes.size() / 2));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "half.pt"); }, {"half.pt", "truncated"});
    // Directory intact but pointing past the end: cut bytes out of the middle.
    std::string middle = bytes;
    middle.erase(200, 300);
    write_bytes(dir / "middle.pt", middle);
    expect_input_error([&] { read_gsplat_checkpoint(dir / "middle.pt"); }, {"middle.pt"});
}

TEST(FormatsGsplatErrors, CorruptStorageIsCaughtByItsCrc) {
    ScratchDir dir;
    std::string bytes = archive_bytes(small_archive());
    // Flip a byte of storage 1 (stored): find the first scale's bytes.
    const GaussianCloud cloud = expected_small_cloud();
    std::string needle;
    append(needle, cloud.log_scales[0]);
    append(needle, cloud.log_scales[3]);
    const size_t at = bytes.find(needle);
    ASSERT_NE(at, std::string::npos);
    bytes[at] ^= 0x40;
    write_bytes(dir / "crc.pt", bytes);
    expect_input_error([&] { read_gsplat_checkpoint(dir / "crc.pt"); }, {"crc.pt", "ckpt/data/1", "CRC mismatch"});
}

TEST(FormatsGsplatErrors, MissingTensorAndWrongShape) {
    ScratchDir dir;
    write_bytes(dir / "noquats.pt", archive_bytes(small_archive(false)));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "noquats.pt"); }, {"noquats.pt", "no 'quats' tensor"});
    write_bytes(dir / "shape.pt", archive_bytes(small_archive(true, {kN, 3})));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "shape.pt"); },
                       {"shape.pt", "tensor 'quats' has shape [5, 3]", "expected [N, 4]"});
}

TEST(FormatsGsplatErrors, TensorReachingBeyondItsStorage) {
    ScratchDir dir;
    // The quaternions' view starts one float too late: its last element lies past storage 0's end.
    Archive archive = small_archive(false);
    Pickle p;
    p.op('}').put(0).mark().text("splats").op('}').put(1).mark();
    p.text("means").tensor("FloatStorage", "0", 2 + kN * 7, 2, {kN, 3}, {3, 1}, 2);
    p.text("quats").tensor("FloatStorage", "0", 2 + kN * 7, 2 + kN * 3 + 1, {kN, 4}, {4, 1}, 2, true);
    p.text("scales").tensor("FloatStorage", "1", kN * 3, 0, {kN, 3}, {1, kN}, 3);
    p.text("opacities").tensor("HalfStorage", "2", kN, 0, {kN}, {1}, 4);
    p.text("sh0").tensor("DoubleStorage", "3", kN * 3, 0, {kN, 1, 3}, {3, 3, 1}, 5);
    p.op('u').op('u');
    archive.pickle = p;
    write_bytes(dir / "reach.pt", archive_bytes(archive));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "reach.pt"); },
                       {"reach.pt", "tensor 'quats'", "reaches element 37", "only 37"});
}

TEST(FormatsGsplatErrors, StorageSmallerThanItsCount) {
    ScratchDir dir;
    Archive archive = small_archive();
    archive.entries[1].data.resize(archive.entries[1].data.size() - 4);  // storage 1 loses a float
    write_bytes(dir / "short.pt", archive_bytes(archive));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "short.pt"); },
                       {"short.pt", "tensor 'scales'", "holds 56 bytes", "15 float32 elements need 60"});
}

TEST(FormatsGsplatErrors, MalformedPickles) {
    ScratchDir dir;
    Archive archive = small_archive();
    std::string pickle = archive.pickle.finish();
    archive.entries.insert(archive.entries.begin(), {"ckpt/data.pkl", pickle.substr(0, pickle.size() / 2)});
    write_bytes(dir / "cut.pt", zip_of(archive.entries));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "cut.pt"); }, {"cut.pt", "data.pkl", "pickle"});

    archive.entries[0].data = std::string("\x80\x02") + "I42\n.";  // protocol-0 INT
    write_bytes(dir / "text.pt", zip_of(archive.entries));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "text.pt"); }, {"text.pt", "unsupported opcode 0x49"});

    Pickle no_splats;
    no_splats.op('}').mark().text("step").integer(1).text("optimizer").op('}').op('u');
    archive.entries[0].data = no_splats.finish();
    write_bytes(dir / "nosplats.pt", zip_of(archive.entries));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "nosplats.pt"); },
                       {"nosplats.pt", "no 'splats'", "top-level keys: step, optimizer"});
}

TEST(FormatsGsplatErrors, ArchiveWithoutAPickle) {
    ScratchDir dir;
    write_bytes(dir / "nopkl.pt", zip_of({{"something/else.txt", "hello"}}));
    expect_input_error([&] { read_gsplat_checkpoint(dir / "nopkl.pt"); }, {"nopkl.pt", "no data.pkl"});
}

TEST(FormatsGsplatSharedData, SnowmikuCheckpointEqualsItsPly) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto path = vksplat::test::shared_data_dir() / "formats" / "snowmiku.gsplat.pt";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
    std::vector<std::string> notes;
    const GaussianCloud ours = read_scene(path, &notes);
    const GaussianCloud ply = read_ply(vksplat::test::shared_data_dir() / "snowmiku" / "point_cloud.ply");
    ASSERT_EQ(ours.size(), 57694u);
    EXPECT_EQ(ours.sh_degree, 3);
    // The same float32 values, reordered from coefficient-major: equal bit for bit.
    expect_same_cloud(ours, ply);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("step 29999"), std::string::npos) << notes[0];
}

}  // namespace
}  // namespace vksplat::io::test
