#pragma once
// Quality of a pruned scene on test views, over the whole picture and inside the subject's region.
// The subject region of a view is fixed by the unpruned scene (eval/subject_region.hpp) or by a
// mask image the user made, so every pruned variant is measured on the same pixels. Subject PSNR
// is the PSNR of those pixels, subject SSIM the mean of the SSIM map over them.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/eval/subject_region.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::jobs {

// Where the subject is: `ball` (automatic when unset), or, with masks_dir, one image per view named
// like its photo (io::find_image), subject where it is brighter than mid-grey.
struct SubjectSpec {
    std::optional<eval::SubjectBall> ball;
    std::optional<std::filesystem::path> masks_dir;
};

// "auto", "x,y,z,r" or the masks folder: what --subject / --subject-masks take. Throws InputError.
SubjectSpec parse_subject_spec(const std::string& subject, const std::string& masks_dir);

// The subject mask of a view (one byte per pixel) from the unpruned scene's render of `camera`.
using SubjectMasks = std::function<std::vector<uint8_t>(const Camera& camera, const RenderOutput& unpruned)>;
// `cameras`: all of the capture's, which the automatic ball is found from. Throws InputError when
// the automatic ball has no focus; mask images are read (and checked) when asked for.
SubjectMasks subject_masks(const SubjectSpec& spec, const std::vector<Camera>& cameras, std::string* description = nullptr);

struct SubjectScores {
    double psnr = 0, ssim = 0;                  // whole picture, mean over views
    double subject_psnr = 0, subject_ssim = 0;  // subject region, mean over the views that have one
};

struct SubjectQuality {
    std::optional<SubjectScores> unpruned_vs_photos;  // with photos only
    std::optional<SubjectScores> pruned_vs_photos;    // with photos only
    SubjectScores pruned_vs_unpruned;
    double subject_fraction = 0;                      // mean share of pixels in the subject region
    size_t views_without_subject = 0;                 // test views whose region is empty
};

// Where comparison sheets go: one PNG per test view, <stem>_subject.png (the test cameras'
// output_stems, jobs/render_views.hpp), of photo | unpruned | pruned | the subject region (the
// unpruned render, dimmed outside it) | the pruned render's error against the photo (else the
// unpruned render), max_error at the top of the ramp.
struct SubjectSheets {
    std::filesystem::path dir;
    float max_error = 0.25f;
    io::WriteMode mode = io::WriteMode::refuse_existing;
};

// Photos are looked up by camera name in images_dir (io::find_image) when it is given.
SubjectQuality measure_subject_quality(Renderer& renderer, const GaussianCloud& unpruned, const GaussianCloud& pruned,
                                       const std::vector<Camera>& test_cameras,
                                       const std::optional<std::filesystem::path>& images_dir,
                                       const RenderSettings& settings, const SubjectMasks& masks,
                                       const std::optional<SubjectSheets>& sheets = {});

}  // namespace vksplat::jobs
