// Renders compared with targets: PSNR (and SSIM) per view and their means.
#include "vksplat/eval/quality.hpp"

#include <stdexcept>
#include <string>

#include "vksplat/eval/metrics.hpp"

namespace vksplat::eval {

TestViews render_targets(Renderer& renderer, const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                         const RenderSettings& settings) {
    renderer.set_scene(cloud);
    TestViews views;
    views.cameras = cameras;
    for (const Camera& camera : cameras) views.targets.push_back(renderer.render(camera, settings).rgb);
    return views;
}

Quality measure_quality(Renderer& renderer, const GaussianCloud& cloud, const TestViews& views,
                        const RenderSettings& settings, bool with_ssim) {
    if (views.targets.size() != views.cameras.size())
        throw std::invalid_argument("eval::measure_quality: " + std::to_string(views.targets.size()) +
                                    " targets for " + std::to_string(views.cameras.size()) + " cameras");
    renderer.set_scene(cloud);
    Quality quality;
    for (size_t v = 0; v < views.cameras.size(); ++v) {
        const RenderOutput image = renderer.render(views.cameras[v], settings);
        if (views.targets[v].size() != image.rgb.size())
            throw std::invalid_argument("eval::measure_quality: target " + std::to_string(v) +
                                        " does not have the camera's size");
        quality.psnr.push_back(eval::psnr(image.rgb.data(), views.targets[v].data(), image.width, image.height));
        quality.mean_psnr += quality.psnr.back();
        if (!with_ssim) continue;
        quality.ssim.push_back(eval::ssim(image.rgb.data(), views.targets[v].data(), image.width, image.height));
        quality.mean_ssim += quality.ssim.back();
    }
    if (!views.cameras.empty()) {
        quality.mean_psnr /= double(views.cameras.size());
        quality.mean_ssim /= double(views.cameras.size());
    }
    return quality;
}

}  // namespace vksplat::eval
