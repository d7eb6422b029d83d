#pragma once
// Quality of a pruned scene on test views, over the whole picture and inside the subject's region.
// The subject region of a view: the pixels where the *unpruned* render's alpha exceeds 0.5 inside
// the central box (the middle two thirds of the width and of the height: [W/6, 5W/6) x [H/6, 5H/6)).
// It is fixed by the unpruned scene, so every pruned variant is measured on the same pixels.
// Subject PSNR is the PSNR of those pixels; subject SSIM is the SSIM of the central box (SSIM
// needs whole windows, so it cannot follow the alpha outline).
#include <filesystem>
#include <optional>
#include <vector>

#include "vksplat/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::jobs {

struct SubjectScores {
    double psnr = 0, ssim = 0;                  // whole picture, mean over views
    double subject_psnr = 0, subject_ssim = 0;  // subject region, mean over views
};

struct SubjectQuality {
    std::optional<SubjectScores> unpruned_vs_photos;  // with photos only
    std::optional<SubjectScores> pruned_vs_photos;    // with photos only
    SubjectScores pruned_vs_unpruned;
    double subject_fraction = 0;                      // mean share of pixels in the subject region
};

// Photos are looked up by camera name in images_dir (io::find_image) when it is given.
SubjectQuality measure_subject_quality(Renderer& renderer, const GaussianCloud& unpruned, const GaussianCloud& pruned,
                                       const std::vector<Camera>& test_cameras,
                                       const std::optional<std::filesystem::path>& images_dir,
                                       const RenderSettings& settings);

}  // namespace vksplat::jobs
