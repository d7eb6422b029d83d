#pragma once
// Quality of a (pruned) scene on held-out views: renders compared with target pictures, which are
// the photos when there are any, else renders of the unpruned scene.
#include <array>
#include <filesystem>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::eval {

struct TestViews {
    std::vector<Camera> cameras;
    std::vector<std::vector<float>> targets;  // per camera: RGB, row-major, the camera's size
    bool photos = false;                      // targets are photos, else renders of the unpruned scene
};

// The renders of `cloud` from `cameras`, as the targets when no photos are available.
TestViews render_targets(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                         const RenderSettings& settings);

// The photos of `cameras` as targets, found in `images_dir` by camera name (io::find_image) and
// composited over `background` where they have alpha. Throws InputError naming the file for a
// missing or unreadable photo, or one whose size is not its camera's.
TestViews photo_targets(const std::vector<Camera>& cameras, const std::filesystem::path& images_dir,
                        const std::array<float, 3>& background);

struct Quality {
    std::vector<double> psnr;  // per view, dB (+infinity where render and target are identical)
    std::vector<double> ssim;  // per view; empty unless asked for
    double mean_psnr = 0;
    double mean_ssim = 0;
};

// Uploads `cloud` and compares its renders with the targets.
Quality measure_quality(Renderer& renderer, const GaussianCloud& cloud, const TestViews& views,
                        const RenderSettings& settings, bool with_ssim);

}  // namespace vksplat::eval
