// The C API (vksplat/vksplat.h): what it renders and prunes is what the C++ API gives, byte for
// byte; bad input comes back as a status and a message naming the problem, never as an exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/dataset.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/version.hpp"
#include "vksplat/vksplat.h"

namespace vksplat::test {
namespace {

// The C struct of a C++ camera, field by field (rotation row-major).
vksplat_camera c_camera(const Camera& camera) {
    vksplat_camera out{};
    out.width = camera.width;
    out.height = camera.height;
    out.fx = camera.fx;
    out.fy = camera.fy;
    out.cx = camera.cx;
    out.cy = camera.cy;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) out.rotation[r * 3 + c] = camera.rotation[c][r];
        out.translation[r] = camera.translation[r];
    }
    return out;
}

// The shared test device, lent to the C API as an application would lend its own.
vksplat_adopted_device lent_device() {
    const gpu::Context& context = shared_test_context();
    vksplat_adopted_device lent{};
    lent.instance = context.instance();
    lent.physical_device = context.physical_device();
    lent.device = context.device();
    lent.queue_family = context.queue_family();
    lent.queue = context.queue();
    // vksplat's own device enables these wherever the driver has them.
    lent.int64_atomics_enabled = context.info().int64_atomics;
    lent.float_atomics_enabled = context.info().float_atomics;
    return lent;
}

class CApiTest : public GpuTest {
protected:
    void SetUp() override {
        dir_ = fresh_test_dir("capi");
        const vksplat_adopted_device lent = lent_device();
        ASSERT_EQ(vksplat_context_adopt(&lent, &context_, &error_), VKSPLAT_OK) << error_.message;
        ASSERT_EQ(vksplat_renderer_create(context_, &renderer_, &error_), VKSPLAT_OK) << error_.message;
    }
    void TearDown() override {
        vksplat_renderer_destroy(renderer_);
        vksplat_context_destroy(context_);
        std::filesystem::remove_all(dir_);
    }

    // `cloud` written as an INRIA PLY, for both APIs to read.
    std::filesystem::path scene_file(const GaussianCloud& cloud, const std::string& name = "scene.ply") {
        const auto path = dir_ / name;
        io::write_scene(cloud, path);
        return path;
    }

    vksplat_scene* load(const std::filesystem::path& path) {
        vksplat_scene* scene = nullptr;
        EXPECT_EQ(vksplat_scene_load(path.c_str(), &scene, &error_), VKSPLAT_OK) << error_.message;
        return scene;
    }

    std::filesystem::path dir_;
    vksplat_context* context_ = nullptr;
    vksplat_renderer* renderer_ = nullptr;
    vksplat_error error_{};
};

uint8_t level(float value) { return uint8_t(std::lround(std::fmin(std::fmax(value, 0.0f), 1.0f) * 255.0f)); }

TEST_F(CApiTest, RendersWhatTheCppApiRendersByteForByte) {
    const auto path = scene_file(random_scene(7, 400, 3));
    // Off the axis and turned, so that a rotation read transposed would show.
    const Camera camera = Camera::look_at({1.0, -0.6, 0.0}, {0.0, 0.0, 5.0}, {0.1, -1.0, 0.0}, 72, 56, 60.0, 60.0);
    RenderSettings cpp_settings;
    cpp_settings.background = {0.1f, 0.3f, 0.5f};
    cpp_settings.max_sh_degree = 2;
    Renderer cpp(context());
    cpp.set_scene(io::read_scene(path));
    const RenderOutput expected = cpp.render(camera, cpp_settings);

    vksplat_scene* scene = load(path);
    ASSERT_EQ(vksplat_renderer_set_scene(renderer_, scene, &error_), VKSPLAT_OK) << error_.message;
    vksplat_scene_destroy(scene);  // the renderer keeps its own copy
    vksplat_render_settings settings = vksplat_render_settings_default();
    for (int c = 0; c < 3; ++c) settings.background[c] = cpp_settings.background[size_t(c)];
    settings.max_sh_degree = 2;
    const vksplat_camera view = c_camera(camera);
    const size_t pixels = size_t(camera.width) * camera.height;

    std::vector<float> rgb(pixels * 3), depth(pixels), alpha(pixels);
    vksplat_image image{VKSPLAT_PIXELS_RGB_FLOAT, rgb.data(), rgb.size() * 4, depth.data(), depth.size() * 4,
                        alpha.data(), alpha.size() * 4};
    ASSERT_EQ(vksplat_render(renderer_, &view, &settings, &image, &error_), VKSPLAT_OK) << error_.message;
    EXPECT_STREQ(error_.message, "");
    EXPECT_EQ(std::memcmp(rgb.data(), expected.rgb.data(), rgb.size() * 4), 0);
    EXPECT_EQ(std::memcmp(depth.data(), expected.depth.data(), depth.size() * 4), 0);
    EXPECT_EQ(std::memcmp(alpha.data(), expected.alpha.data(), alpha.size() * 4), 0);

    std::vector<uint8_t> rgba(pixels * 4);
    image = {VKSPLAT_PIXELS_RGBA8, rgba.data(), rgba.size(), nullptr, 0, nullptr, 0};
    ASSERT_EQ(vksplat_render(renderer_, &view, &settings, &image, nullptr), VKSPLAT_OK);
    size_t differing = 0;
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < 4; ++c)
            differing += rgba[i * 4 + c] != level(c < 3 ? expected.rgb[i * 3 + c] : expected.alpha[i]);
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(std::count_if(rgba.begin(), rgba.end(), [&](uint8_t v) { return v != rgba[0]; }), 100);
}

TEST_F(CApiTest, RecordsIntoTheCallersBufferWhatItRenders) {
    const auto path = scene_file(random_scene(8, 200, 1));
    vksplat_scene* scene = load(path);
    ASSERT_EQ(vksplat_renderer_set_scene(renderer_, scene, &error_), VKSPLAT_OK) << error_.message;
    vksplat_scene_destroy(scene);
    const Camera camera = forward_camera(48, 40, 40.0);
    const vksplat_camera view = c_camera(camera);
    const size_t pixels = size_t(camera.width) * camera.height;
    std::vector<float> rgb(pixels * 3), alpha(pixels);
    const vksplat_image image{VKSPLAT_PIXELS_RGB_FLOAT, rgb.data(), rgb.size() * 4, nullptr, 0, alpha.data(),
                              alpha.size() * 4};
    ASSERT_EQ(vksplat_render(renderer_, &view, nullptr, &image, &error_), VKSPLAT_OK) << error_.message;

    gpu::Buffer target(context(), pixels * 16, gpu::MemoryKind::readback, "C API target");
    gpu::CommandStream ours(context());
    ours.begin();
    vksplat_target into{};
    into.buffer = target.handle();
    into.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    ASSERT_EQ(vksplat_record(renderer_, ours.handle(), &view, nullptr, &into, &error_), VKSPLAT_OK) << error_.message;
    ours.submit_and_wait();
    const auto* got = static_cast<const float*>(target.mapped());
    for (size_t i = 0; i < pixels; ++i) {
        for (size_t c = 0; c < 3; ++c) ASSERT_EQ(got[i * 4 + c], rgb[i * 3 + c]) << "pixel " << i;
        ASSERT_EQ(got[i * 4 + 3], alpha[i]) << "pixel " << i;
    }

    into.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // a format record() does not write
    EXPECT_EQ(vksplat_record(renderer_, ours.handle(), &view, nullptr, &into, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_NE(std::string(error_.message).find("vksplat_record: "), std::string::npos) << error_.message;
}

TEST_F(CApiTest, PrunesAsThePruneJobDoes) {
    // The views come from a camera file, read by both APIs.
    const auto camera_file = dir_ / "cameras.json";
    io::write_inria_cameras(camera_file, row_of_five_views());
    const std::vector<Camera> cameras = io::read_cameras(camera_file);
    const auto path = scene_file(random_scene(9, 600, 1));
    vksplat_camera* views = nullptr;
    size_t view_count = 0;
    ASSERT_EQ(vksplat_cameras_load(camera_file.c_str(), &views, &view_count, &error_), VKSPLAT_OK) << error_.message;
    ASSERT_EQ(view_count, cameras.size());
    for (size_t i = 0; i < view_count; ++i) {
        const vksplat_camera same = c_camera(cameras[i]);
        EXPECT_EQ(std::memcmp(&views[i], &same, sizeof same), 0) << "camera " << i;
    }
    vksplat_scene* scene = load(path);
    size_t count = 0;
    // What `vksplat prune --method M --ratio 0.4` keeps when it scores over all five views; fisher
    // is the one method whose totals need more than the renders' statistics.
    const std::pair<vksplat_score_method, prune::ScoreMethod> methods[] = {
        {VKSPLAT_SCORE_FOOTPRINT, prune::ScoreMethod::footprint}, {VKSPLAT_SCORE_FISHER, prune::ScoreMethod::fisher}};
    for (const auto& [c_method, method] : methods) {
        SCOPED_TRACE(std::string(prune::to_string(method)));
        jobs::PruneOptions options;
        options.method = method;
        options.selector = jobs::DropRatio{0.4};
        options.train_views = {0, 1, 2, 3, 4};
        options.test_views = {0};
        options.out = dir_ / ("job_" + std::string(prune::to_string(method)) + ".ply");
        Renderer cpp(context());
        jobs::prune_scene(cpp, io::read_scene(path), cameras, options);
        const GaussianCloud expected = io::read_scene(options.out);

        vksplat_prune_options asked{};
        asked.method = c_method;
        asked.ratio = 0.4;
        asked.views = views;
        asked.view_count = view_count;
        vksplat_scene* pruned = nullptr;
        ASSERT_EQ(vksplat_prune(renderer_, scene, &asked, &pruned, &error_), VKSPLAT_OK) << error_.message;
        const auto saved = dir_ / ("capi_" + std::string(prune::to_string(method)) + ".ply");
        ASSERT_EQ(vksplat_scene_save(pruned, saved.c_str(), 0, &error_), VKSPLAT_OK) << error_.message;
        ASSERT_EQ(vksplat_scene_info(pruned, &count, nullptr, &error_), VKSPLAT_OK);
        EXPECT_EQ(count, expected.size());
        EXPECT_LE(count, 600u - 240u);
        const GaussianCloud got = io::read_scene(saved);
        EXPECT_EQ(got.positions, expected.positions);
        EXPECT_EQ(got.sh, expected.sh);
        vksplat_scene_destroy(pruned);
    }

    // Without views: opacity needs none, the view-based methods say they do.
    vksplat_prune_options by_opacity{};
    by_opacity.method = VKSPLAT_SCORE_OPACITY;
    by_opacity.ratio = 0.5;
    vksplat_scene* half = nullptr;
    ASSERT_EQ(vksplat_prune(nullptr, scene, &by_opacity, &half, &error_), VKSPLAT_OK) << error_.message;
    ASSERT_EQ(vksplat_scene_info(half, &count, nullptr, &error_), VKSPLAT_OK);
    EXPECT_EQ(count, 300u);
    by_opacity.method = VKSPLAT_SCORE_BLEND;
    vksplat_scene* refused = nullptr;
    EXPECT_EQ(vksplat_prune(renderer_, scene, &by_opacity, &refused, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_EQ(refused, nullptr);
    EXPECT_STREQ(error_.message,
                 "vksplat_prune: options->method blend scores over views: give at least one in options->views");
    by_opacity.method = VKSPLAT_SCORE_OPACITY;
    by_opacity.ratio = 1.5;
    EXPECT_EQ(vksplat_prune(nullptr, scene, &by_opacity, &refused, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error_.message).find("1.5"), std::string::npos) << error_.message;
    vksplat_scene_destroy(half);
    vksplat_cameras_free(views);
    vksplat_scene_destroy(scene);
}

TEST_F(CApiTest, BadInputGivesItsStatusAndAMessageNamingIt) {
    // A missing file, named.
    vksplat_scene* scene = reinterpret_cast<vksplat_scene*>(&error_);  // not NULL: a failed call clears it
    const auto missing = dir_ / "missing.ply";
    EXPECT_EQ(vksplat_scene_load(missing.c_str(), &scene, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_EQ(scene, nullptr);
    EXPECT_NE(std::string(error_.message).find(missing.string()), std::string::npos) << error_.message;

    // A missing camera file, named; no cameras come back.
    vksplat_camera* cameras = reinterpret_cast<vksplat_camera*>(&error_);
    size_t camera_count = 7;
    const auto no_cameras = dir_ / "cameras.json";
    EXPECT_EQ(vksplat_cameras_load(no_cameras.c_str(), &cameras, &camera_count, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_EQ(cameras, nullptr);
    EXPECT_EQ(camera_count, 0u);
    EXPECT_NE(std::string(error_.message).find(no_cameras.string()), std::string::npos) << error_.message;

    // A truncated PLY, named, and said to be truncated.
    const auto whole = scene_file(random_scene(3, 50, 0));
    const auto cut = dir_ / "cut.ply";
    std::filesystem::copy_file(whole, cut);
    std::filesystem::resize_file(cut, std::filesystem::file_size(whole) - 100);
    EXPECT_EQ(vksplat_scene_load(cut.c_str(), &scene, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error_.message).find(cut.string()), std::string::npos) << error_.message;
    EXPECT_NE(std::string(error_.message).find("truncated"), std::string::npos) << error_.message;

    // Buffers too small for the picture, before anything is rendered.
    scene = load(whole);
    ASSERT_EQ(vksplat_renderer_set_scene(renderer_, scene, &error_), VKSPLAT_OK) << error_.message;
    const vksplat_camera view = c_camera(forward_camera(32, 24, 30.0));
    std::vector<uint8_t> rgba(32 * 24 * 4);
    vksplat_image image{VKSPLAT_PIXELS_RGBA8, rgba.data(), rgba.size() - 1, nullptr, 0, nullptr, 0};
    EXPECT_EQ(vksplat_render(renderer_, &view, nullptr, &image, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message,
                 "vksplat_render: image->pixels_size is 3071 bytes; a 32 x 24 RGBA8 picture needs 3072");
    image.pixels_size = rgba.size();
    image.format = VKSPLAT_PIXELS_RGB_FLOAT;  // 12 bytes a pixel
    EXPECT_EQ(vksplat_render(renderer_, &view, nullptr, &image, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_NE(std::string(error_.message).find("RGB float picture needs 9216"), std::string::npos) << error_.message;
    image.format = VKSPLAT_PIXELS_RGBA8;
    std::vector<float> depth(10);
    image.depth = depth.data();
    image.depth_size = depth.size() * 4;
    EXPECT_EQ(vksplat_render(renderer_, &view, nullptr, &image, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_NE(std::string(error_.message).find("image->depth_size is 40 bytes"), std::string::npos) << error_.message;
    image.depth = nullptr;

    // An invalid camera is bad input, named.
    vksplat_camera flat = view;
    flat.fx = 0;
    EXPECT_EQ(vksplat_render(renderer_, &flat, nullptr, &image, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error_.message).find("camera 'vksplat_camera'"), std::string::npos) << error_.message;
    // A background out of range too.
    vksplat_render_settings settings = vksplat_render_settings_default();
    settings.background[1] = 2.0f;
    EXPECT_EQ(vksplat_render(renderer_, &view, &settings, &image, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error_.message).find("background"), std::string::npos) << error_.message;

    // An existing file is not overwritten unless asked.
    EXPECT_EQ(vksplat_scene_save(scene, whole.c_str(), 0, &error_), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error_.message).find(whole.string()), std::string::npos) << error_.message;
    EXPECT_EQ(vksplat_scene_save(scene, whole.c_str(), 1, &error_), VKSPLAT_OK) << error_.message;

    // Arrays missing for a scene of some Gaussians, and an SH degree out of range.
    vksplat_scene_data data{};
    data.count = 2;
    vksplat_scene* made = nullptr;
    EXPECT_EQ(vksplat_scene_create(&data, &made, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_scene_create: data->positions is NULL");
    data.sh_degree = 4;
    EXPECT_EQ(vksplat_scene_create(&data, &made, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_scene_create: data->sh_degree is 4; it must be 0 to 3");
    EXPECT_EQ(made, nullptr);
    vksplat_scene_destroy(scene);
}

TEST_F(CApiTest, NullHandlesAreRefusedByName) {
    const vksplat_camera view = c_camera(forward_camera(8, 8, 8.0));
    uint8_t pixels[8 * 8 * 4];
    const vksplat_image image{VKSPLAT_PIXELS_RGBA8, pixels, sizeof pixels, nullptr, 0, nullptr, 0};
    vksplat_scene* scene = nullptr;
    vksplat_renderer* renderer = nullptr;
    size_t count = 0;
    EXPECT_EQ(vksplat_render(nullptr, &view, nullptr, &image, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_render: renderer is NULL");
    EXPECT_EQ(vksplat_render(renderer_, nullptr, nullptr, &image, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_render: camera is NULL");
    EXPECT_EQ(vksplat_render(renderer_, &view, nullptr, nullptr, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_render: image is NULL");
    EXPECT_EQ(vksplat_renderer_create(nullptr, &renderer, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_renderer_create: context is NULL");
    EXPECT_EQ(vksplat_renderer_set_scene(renderer_, nullptr, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_renderer_set_scene: scene is NULL");
    EXPECT_EQ(vksplat_scene_load(nullptr, &scene, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_scene_load: path is NULL");
    EXPECT_EQ(vksplat_scene_load("x.ply", nullptr, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_scene_load: scene is NULL");
    EXPECT_EQ(vksplat_scene_info(nullptr, &count, nullptr, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_scene_info: scene is NULL");
    EXPECT_EQ(vksplat_context_adopt(nullptr, nullptr, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_context_adopt: context is NULL");
    EXPECT_EQ(vksplat_prune(renderer_, nullptr, nullptr, &scene, &error_), VKSPLAT_INVALID_ARGUMENT);
    EXPECT_STREQ(error_.message, "vksplat_prune: options is NULL");
    // No error struct: the status alone.
    EXPECT_EQ(vksplat_render(nullptr, &view, nullptr, &image, nullptr), VKSPLAT_INVALID_ARGUMENT);
    // Destroying nothing is allowed.
    vksplat_scene_destroy(nullptr);
    vksplat_cameras_free(nullptr);
    vksplat_renderer_destroy(nullptr);
    vksplat_context_destroy(nullptr);
}

// An adopted device with a null queue is refused by the library (GpuError), and the message says why.
TEST_F(CApiTest, AnAdoptedDeviceWithoutAQueueIsAGpuError) {
    vksplat_adopted_device lent = lent_device();
    lent.queue = VK_NULL_HANDLE;
    vksplat_context* context = nullptr;
    EXPECT_EQ(vksplat_context_adopt(&lent, &context, &error_), VKSPLAT_GPU_ERROR);
    EXPECT_EQ(context, nullptr);
    EXPECT_NE(std::string(error_.message).find("queue"), std::string::npos) << error_.message;
}

TEST(CApi, OpensADeviceOfItsOwn) {
    const std::string wanted = test_context_options().device;
    vksplat_context_options options{};
    options.device = wanted.c_str();
    vksplat_context* context = nullptr;
    vksplat_error error{};
    ASSERT_EQ(vksplat_context_create(&options, &context, &error), VKSPLAT_OK) << error.message;
    char name[256];
    ASSERT_EQ(vksplat_context_device_name(context, name, sizeof name, &error), VKSPLAT_OK) << error.message;
    EXPECT_EQ(std::string(name), shared_test_context().info().name);
    char short_name[4];
    ASSERT_EQ(vksplat_context_device_name(context, short_name, sizeof short_name, &error), VKSPLAT_OK);
    EXPECT_EQ(std::string(short_name), std::string(name).substr(0, 3));
    vksplat_context_destroy(context);

    options.device = "no device is called this";
    EXPECT_EQ(vksplat_context_create(&options, &context, &error), VKSPLAT_GPU_ERROR);
    EXPECT_EQ(context, nullptr);
    EXPECT_NE(std::string(error.message).find("no device is called this"), std::string::npos) << error.message;
}

TEST(CApi, BuildsACameraAndASceneFromPlainArrays) {
    const double eye[3] = {0, -4, 1}, target[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    vksplat_camera camera{};
    vksplat_error error{};
    ASSERT_EQ(vksplat_camera_look_at(eye, target, up, 64, 48, 50, 50, &camera, &error), VKSPLAT_OK) << error.message;
    const Camera expected = Camera::look_at({0, -4, 1}, {0, 0, 0}, {0, 0, 1}, 64, 48, 50, 50);
    const vksplat_camera same = c_camera(expected);
    EXPECT_EQ(std::memcmp(&camera, &same, sizeof camera), 0);
    EXPECT_EQ(vksplat_camera_look_at(eye, eye, up, 64, 48, 50, 50, &camera, &error), VKSPLAT_INVALID_INPUT);
    EXPECT_NE(std::string(error.message).find("coincide"), std::string::npos) << error.message;

    const GaussianCloud cloud = random_scene(5, 20, 2);
    const vksplat_scene_data data{cloud.size(), cloud.sh_degree, cloud.positions.data(), cloud.log_scales.data(),
                                  cloud.rotations.data(), cloud.opacity_logits.data(), cloud.sh.data()};
    vksplat_scene* scene = nullptr;
    ASSERT_EQ(vksplat_scene_create(&data, &scene, &error), VKSPLAT_OK) << error.message;
    size_t count = 0;
    int degree = -1;
    ASSERT_EQ(vksplat_scene_info(scene, &count, &degree, &error), VKSPLAT_OK);
    EXPECT_EQ(count, 20u);
    EXPECT_EQ(degree, 2);
    vksplat_scene_destroy(scene);
}

TEST(CApi, SaysItsVersionAndStatusNames) {
    EXPECT_STREQ(vksplat_version(), kVersion);
    EXPECT_STREQ(vksplat_status_name(VKSPLAT_INVALID_INPUT), "VKSPLAT_INVALID_INPUT");
    EXPECT_STREQ(vksplat_status_name(static_cast<vksplat_status>(99)), "unknown status");
}

}  // namespace
}  // namespace vksplat::test
