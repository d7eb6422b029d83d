// convert_scene: a generated scene goes through every writable format and back, and the picture
// it makes stays the same (exactly for ply, within each format's rounding for spz, splat and sog);
// mistakes are refused before anything is read or written.
#include <gtest/gtest.h>

#include <algorithm>

#include "io/io_test_helpers.hpp"
#include "support/scenes.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/convert_scene.hpp"
#include "vksplat/reference/rasterizer.hpp"

namespace vksplat::jobs {
namespace {

using io::test::expect_input_error;
using io::test::ScratchDir;

// 40 opaque-ish splats in front of the camera, SH degree 0 so that every format can hold them.
GaussianCloud small_scene() { return test::random_scene(7, 40, 0, 3.0f, 6.0f, 0.05f, 0.3f, 1.0f); }

double render_psnr(const GaussianCloud& a, const GaussianCloud& b) {
    const Camera camera = test::forward_camera(48, 32, 40.0);
    const RenderSettings settings;
    const RenderOutput x = reference::render(a, camera, settings), y = reference::render(b, camera, settings);
    // The comparison means something only if the scene covers the picture.
    EXPECT_GT(*std::max_element(x.alpha.begin(), x.alpha.end()), 0.9f);
    return eval::psnr(x.rgb.data(), y.rgb.data(), camera.width, camera.height);
}

TEST(ConvertScene, EveryWritableFormatRoundTripsToTheSamePicture) {
    ScratchDir dir;
    const GaussianCloud scene = small_scene();
    io::write_scene(scene, dir / "scene.ply");
    struct Case {
        const char* file;
        double min_psnr;  // of the render after ply -> format -> ply against the original's
    };
    for (const Case c :
         {Case{"scene.ply", 1e9}, Case{"scene.splat", 45.0}, Case{"scene.spz", 45.0}, Case{"scene.sog", 45.0}}) {
        SCOPED_TRACE(c.file);
        const std::string there = std::string("to_") + c.file;
        const std::string back = there + ".ply";
        const ConvertResult out = convert_scene(dir / "scene.ply", dir / there);
        EXPECT_EQ(out.gaussians, scene.size());
        EXPECT_EQ(out.output_format, io::scene_format_of(dir / there));
        const ConvertResult in = convert_scene(dir / there, dir / back);
        EXPECT_EQ(in.input_format, out.output_format);
        EXPECT_EQ(in.output_format, "ply");
        const GaussianCloud round_trip = io::read_scene(dir / back);
        ASSERT_EQ(round_trip.size(), scene.size());
        if (c.min_psnr > 1e8)
            io::test::expect_same_cloud(round_trip, scene);
        else
            EXPECT_GT(render_psnr(scene, round_trip), c.min_psnr);
    }
}

TEST(ConvertScene, SplatSaysItDropsShBands) {
    ScratchDir dir;
    io::write_scene(test::random_scene(3, 5, 2), dir / "scene.ply");
    const ConvertResult result = convert_scene(dir / "scene.ply", dir / "scene.splat");
    EXPECT_EQ(result.input_sh_degree, 2);
    EXPECT_EQ(result.output_sh_degree, 0);
    ASSERT_FALSE(result.notes.empty());
    EXPECT_NE(result.notes.back().find("SH degree 2 reduced to 0"), std::string::npos) << result.notes.back();
}

TEST(ConvertScene, SogSaysWhatItRounds) {
    ScratchDir dir;
    io::write_scene(test::random_scene(3, 5, 2), dir / "scene.ply");
    const ConvertResult result = convert_scene(dir / "scene.ply", dir / "scene.sog");
    EXPECT_EQ(result.output_sh_degree, 2);
    ASSERT_FALSE(result.notes.empty());
    EXPECT_NE(result.notes.back().find("palette of at most 4096"), std::string::npos) << result.notes.back();
}

TEST(ConvertScene, NamedFormatsOverrideExtensions) {
    ScratchDir dir;
    io::write_scene(small_scene(), dir / "scene.ply");
    const ConvertResult result = convert_scene(dir / "scene.ply", dir / "scene.bin", {"", "SPZ"});
    EXPECT_EQ(result.output_format, "spz");
    EXPECT_EQ(convert_scene(dir / "scene.bin", dir / "again.ply", {"spz", ""}).gaussians, 40u);
}

TEST(ConvertScene, ExistingOutputIsKeptWithoutOverwrite) {
    ScratchDir dir;
    io::write_scene(small_scene(), dir / "scene.ply");
    io::test::write_bytes(dir / "taken.spz", "keep me");
    expect_input_error([&] { convert_scene(dir / "scene.ply", dir / "taken.spz"); }, {"taken.spz", "already exists"});
    EXPECT_EQ(io::test::read_bytes(dir / "taken.spz"), "keep me");
    convert_scene(dir / "scene.ply", dir / "taken.spz", {"", "", io::WriteMode::overwrite});
    EXPECT_EQ(io::read_scene(dir / "taken.spz").size(), 40u);
}

// The output's name decides its format: an existing out.ply that is really another format (read
// as such by its header, or not a PLY at all) is replaced by a plain PLY, not taken as a model.
TEST(ConvertScene, AnExistingOutputHasNoSayInItsFormat) {
    ScratchDir dir;
    const GaussianCloud scene = small_scene();
    io::write_scene(scene, dir / "scene.ply");
    io::write_scene(scene, dir / "real.spz");
    io::write_scene(scene, dir / "real.splat");
    // A compressed PLY's header (chunks, packed vertices): read as compressed-ply, a read-only format.
    io::test::write_bytes(dir / "real.compressed.ply",
                          "ply\nformat binary_little_endian 1.0\nelement chunk 1\nproperty float min_x\n"
                          "element vertex 1\nproperty uint packed_position\nend_header\n");
    ASSERT_EQ(io::scene_format_of(dir / "real.compressed.ply"), "compressed-ply");
    for (const char* impostor : {"real.spz", "real.splat", "real.compressed.ply"}) {
        SCOPED_TRACE(impostor);
        std::filesystem::copy_file(dir / impostor, dir / "out.ply", std::filesystem::copy_options::overwrite_existing);
        const ConvertResult result = convert_scene(dir / "scene.ply", dir / "out.ply", {"", "", io::WriteMode::overwrite});
        EXPECT_EQ(result.output_format, "ply");
        EXPECT_EQ(io::scene_format_of(dir / "out.ply"), "ply");
        io::test::expect_same_cloud(io::read_scene(dir / "out.ply"), scene);
    }
}

TEST(ConvertScene, MistakesAreRefusedBeforeWriting) {
    ScratchDir dir;
    io::write_scene(small_scene(), dir / "scene.ply");
    expect_input_error([&] { convert_scene(dir / "absent.ply", dir / "x.spz"); }, {"absent.ply", "no such file"});
    expect_input_error([&] { convert_scene(dir / "scene.ply", dir / "x.obj"); },
                       {"x.obj", "cannot write a scene as '.obj'", ".compressed.ply"});
    expect_input_error([&] { convert_scene(dir / "scene.ply", dir / "x.ply", {"", "ksplat"}); },
                       {"x.ply", "unknown scene format 'ksplat'"});
    expect_input_error([&] { convert_scene(dir / "scene.ply", dir / "x.pt"); }, {"x.pt", "cannot write format 'gsplat-pt'"});
    expect_input_error([&] { convert_scene(dir / "scene.ply", dir / "scene.ply", {"", "", io::WriteMode::overwrite}); },
                       {"scene.ply", "is an input of this command"});
    for (const char* name : {"x.spz", "x.obj", "x.ply", "x.pt"}) EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
}

}  // namespace
}  // namespace vksplat::jobs
