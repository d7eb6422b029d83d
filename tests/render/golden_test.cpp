// Real scenes from ../shared/data against the reference CUDA rasterizer's own renders (golden/)
// and against its PSNR on the held-out photos (psnr_reference.json). Skipped, with a message,
// where the data is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/gpu_fixture.hpp"
#include "support/image_compare.hpp"
#include "support/test_data.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

struct SceneCase {
    const char* name;
    std::array<float, 3> background;
};

void PrintTo(const SceneCase& scene, std::ostream* out) { *out << scene.name; }

class Golden : public GpuTest, public ::testing::WithParamInterface<SceneCase> {
protected:
    void load() {
        const auto dir = shared_data_dir() / GetParam().name;
        cloud = io::read_ply(dir / "point_cloud.ply");
        cameras = io::read_cameras(dir / "cameras.json");
        settings.background = GetParam().background;
    }
    GaussianCloud cloud;
    std::vector<Camera> cameras;
    RenderSettings settings;
};

std::vector<float> quantize8(const std::vector<float>& rgb) {
    std::vector<float> out(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) out[i] = std::round(std::clamp(rgb[i], 0.0f, 1.0f) * 255.0f) / 255.0f;
    return out;
}

TEST_P(Golden, MatchesTheReferenceRenders) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    load();
    Renderer renderer(context());
    renderer.set_scene(cloud);
    const auto dir = shared_data_dir() / GetParam().name / "golden";
    for (int k = 0; k < 4; ++k) {
        char file[32];
        std::snprintf(file, sizeof(file), "%05d.png", k);
        const RenderOutput out = renderer.render(cameras[k], settings);
        const io::ImageRGB golden = io::read_image_rgb(dir / file, settings.background);
        ASSERT_EQ(golden.width, out.width);
        ASSERT_EQ(golden.height, out.height);
        // Compare what a saved 8-bit picture holds: the golden images are 8-bit.
        const ImageDiff diff = compare(quantize8(out.rgb), golden.rgb);
        std::printf("[golden] %s view %d: PSNR %.2f dB, %.4f%% of values within 2/255, max error %.4f, %.2f ms GPU\n",
                    GetParam().name, k, diff.psnr, 100.0 * diff.fraction_within(2.0 / 255.0 + 1e-6), diff.max_abs,
                    renderer.last_frame().gpu_milliseconds);
        EXPECT_GE(diff.psnr, 50.0) << GetParam().name << " view " << k;
        EXPECT_GE(diff.fraction_within(2.0 / 255.0 + 1e-6), 0.999) << GetParam().name << " view " << k;
    }
}

TEST_P(Golden, MatchesTheReferencePsnrOnTheTestViews) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    load();
    const auto dir = shared_data_dir() / GetParam().name;
    std::ifstream file(dir / "psnr_reference.json");
    const auto expected = nlohmann::json::parse(file);
    Renderer renderer(context());
    renderer.set_scene(cloud);
    double sum = 0;
    constexpr int kTestViews = 13;
    for (int k = 0; k < kTestViews; ++k) {
        const RenderOutput out = renderer.render(cameras[k], settings);
        const io::ImageRGB photo = io::read_image_rgb(io::find_image(dir / "images", cameras[k].name), settings.background);
        const double psnr = eval::psnr(quantize8(out.rgb).data(), photo.rgb.data(), out.width, out.height);
        char key[32];
        std::snprintf(key, sizeof(key), "%05d.png", k);
        EXPECT_NEAR(psnr, expected[key].get<double>(), 0.05) << GetParam().name << " view " << k;
        sum += psnr;
    }
    std::printf("[golden] %s: mean PSNR vs photos %.3f dB (reference %.3f dB)\n", GetParam().name, sum / kTestViews,
                expected["mean"].get<double>());
    EXPECT_NEAR(sum / kTestViews, expected["mean"].get<double>(), 0.05);
}

INSTANTIATE_TEST_SUITE_P(RealScenes, Golden,
                         ::testing::Values(SceneCase{"lego", {1.0f, 1.0f, 1.0f}}, SceneCase{"snowmiku", {0.0f, 0.0f, 0.0f}}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vksplat::test
