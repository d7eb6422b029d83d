// read_scene and write_scene: the format follows the extension (any case; .compressed.ply for the
// compressed flavour when writing, the header when reading) or an explicit name, and unknown
// extensions, unknown names and read-only formats are refused with the list of what is supported.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

// Values every writable format holds well: moderate positions, colours, scales.
GaussianCloud tame_cloud(size_t count, int sh_degree) {
    GaussianCloud cloud = random_cloud(count, sh_degree, 31);
    for (float& v : cloud.sh) v *= 0.3f;
    return cloud;
}

TEST(FormatsSceneFiles, FormatsAreListed) {
    EXPECT_EQ(scene_formats(),
              (std::vector<std::string>{"ply", "compressed-ply", "splat", "spz", "spz-v4", "sog", "gltf", "gsplat-pt"}));
}

TEST(FormatsSceneFiles, ExtensionChoosesTheFormat) {
    ScratchDir dir;
    EXPECT_EQ(scene_format_of(dir / "a.ply"), "ply");  // absent: the header cannot be looked at
    EXPECT_EQ(scene_format_of(dir / "a.compressed.ply"), "compressed-ply");
    EXPECT_EQ(scene_format_named(dir / "a.Compressed.PLY"), "compressed-ply");
    EXPECT_EQ(scene_format_named(dir / "compressed.ply"), "ply");
    EXPECT_EQ(scene_format_of(dir / "a.splat"), "splat");
    EXPECT_EQ(scene_format_of(dir / "a.SPZ"), "spz");
    EXPECT_EQ(scene_format_of(dir / "a.pt"), "gsplat-pt");
    EXPECT_EQ(scene_format_of(dir / "a.pth"), "gsplat-pt");
    EXPECT_EQ(scene_format_of(dir / "a.glb"), "gltf");
    EXPECT_EQ(scene_format_of(dir / "a.Sog"), "sog");
    EXPECT_EQ(scene_format_of(dir / "META.json"), "sog");
    expect_input_error([&] { scene_format_of(dir / "cameras.json"); }, {"cameras.json", "'.json'"});
    expect_input_error([&] { scene_format_of(dir / "a.obj"); },
                       {"a.obj", "unknown scene file extension '.obj'", ".ply, .splat, .spz, .sog, meta.json (SOG), .glb, .pt"});
    expect_input_error([&] { scene_format_of(dir / "noext"); }, {"noext", "has no extension", ".ply"});
}

TEST(FormatsSceneFiles, EveryWritableFormatRoundTripsThroughTheDispatcher) {
    ScratchDir dir;
    const GaussianCloud cloud = tame_cloud(50, 3);
    write_scene(cloud, dir / "scene.ply");
    expect_same_cloud(read_scene(dir / "scene.ply"), cloud);

    write_scene(cloud, dir / "scene.spz");
    const GaussianCloud spz = read_scene(dir / "scene.spz");
    EXPECT_EQ(spz.sh_degree, 3);
    EXPECT_EQ(spz.size(), cloud.size());
    for (size_t i = 0; i < cloud.positions.size(); ++i) EXPECT_NEAR(spz.positions[i], cloud.positions[i], 1.0 / 8192);

    write_scene(cloud, dir / "scene.compressed.ply");
    EXPECT_TRUE(is_compressed_ply(dir / "scene.compressed.ply"));
    EXPECT_EQ(scene_format_of(dir / "scene.compressed.ply"), "compressed-ply");
    const GaussianCloud compressed = read_scene(dir / "scene.compressed.ply");
    EXPECT_EQ(compressed.sh_degree, 3);
    EXPECT_EQ(compressed.size(), cloud.size());

    write_scene(cloud, dir / "scene.sog");
    const GaussianCloud sog = read_scene(dir / "scene.sog");
    EXPECT_EQ(sog.sh_degree, 3);
    EXPECT_EQ(sog.size(), cloud.size());

    write_scene(cloud, dir / "SCENE.SPLAT");
    const GaussianCloud splat = read_scene(dir / "SCENE.SPLAT");
    EXPECT_EQ(splat.sh_degree, 0);
    EXPECT_EQ(splat.positions, cloud.positions);
}

TEST(FormatsSceneFiles, ExplicitFormatOverridesTheExtension) {
    ScratchDir dir;
    const GaussianCloud cloud = tame_cloud(10, 1);
    write_scene(cloud, dir / "scene.bin", WriteMode::refuse_existing, "spz");
    const std::string bytes = read_bytes(dir / "scene.bin");
    ASSERT_GE(bytes.size(), 2u);
    EXPECT_EQ(static_cast<uint8_t>(bytes[0]), 0x1f);
    write_scene(cloud, dir / "scene4.bin", WriteMode::refuse_existing, "SPZ-V4");
    EXPECT_EQ(read_bytes(dir / "scene4.bin").substr(0, 4), "NGSP");
    EXPECT_EQ(read_scene(dir / "scene4.bin", nullptr, "spz").size(), 10u);
    EXPECT_EQ(read_scene(dir / "scene.bin", nullptr, "SPZ").size(), 10u);
    write_scene(cloud, dir / "other.dat", WriteMode::refuse_existing, "ply");
    expect_same_cloud(read_scene(dir / "other.dat", nullptr, "ply"), cloud);
    // A plain PLY under the compressed name: the name picks the writer, the header the reader.
    write_scene(cloud, dir / "plain.compressed.ply", WriteMode::refuse_existing, "ply");
    expect_same_cloud(read_scene(dir / "plain.compressed.ply"), cloud);
    write_scene(cloud, dir / "packed.ply", WriteMode::refuse_existing, "compressed-ply");
    EXPECT_EQ(read_scene(dir / "packed.ply", nullptr, "ply").size(), 10u);
}

TEST(FormatsSceneFiles, UnknownNamesAndReadOnlyFormatsAreRefused) {
    ScratchDir dir;
    const GaussianCloud cloud = tame_cloud(2, 0);
    const std::string writable = ".ply, .compressed.ply, .splat, .spz, .sog, meta.json (SOG), .glb";
    expect_input_error([&] { write_scene(cloud, dir / "scene.obj"); },
                       {"scene.obj", "cannot write a scene as '.obj'", writable});
    expect_input_error([&] { check_scene_writable(dir / "noext"); }, {"noext", "without an extension", writable});
    expect_input_error([&] { write_scene(cloud, dir / "scene.ply", WriteMode::refuse_existing, "ksplat"); },
                       {"scene.ply", "unknown scene format 'ksplat'", "ply, compressed-ply, splat, spz, spz-v4, sog, gltf, gsplat-pt"});
    expect_input_error([&] { write_scene(cloud, dir / "scene.pt"); },
                       {"scene.pt", "cannot write format 'gsplat-pt'", "read-only", writable});
    expect_input_error([&] { write_scene(cloud, dir / "scene.ply", WriteMode::refuse_existing, "gsplat-pt"); },
                       {"scene.ply", "read-only"});
    EXPECT_FALSE(std::filesystem::exists(dir / "scene.pt"));
    EXPECT_FALSE(std::filesystem::exists(dir / "scene.obj"));
    expect_input_error([&] { read_scene(dir / "scene.xyz"); }, {"scene.xyz", "unknown scene file extension"});
    expect_input_error([&] { read_scene(dir / "absent.spz"); }, {"absent.spz", "no such file"});
    expect_input_error([&] { read_scene(dir / "absent.ply"); }, {"absent.ply", "no such file"});
}

TEST(FormatsSceneFiles, WriteModeIsHonoured) {
    ScratchDir dir;
    const GaussianCloud cloud = tame_cloud(3, 0);
    write_scene(cloud, dir / "scene.spz");
    expect_input_error([&] { write_scene(cloud, dir / "scene.spz"); }, {"scene.spz"});
    EXPECT_NO_THROW(write_scene(cloud, dir / "scene.spz", WriteMode::overwrite));
}

}  // namespace
}  // namespace vksplat::io::test
