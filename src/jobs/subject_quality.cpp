// Whole-picture and subject-region quality of a pruned scene (see subject_quality.hpp).
#include "vksplat/jobs/subject_quality.hpp"

#include <cmath>
#include <cstdio>

#include "vksplat/error.hpp"
#include "vksplat/report/comparison_sheet.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/jobs/render_views.hpp"

namespace vksplat::jobs {
namespace {

std::vector<uint8_t> mask_from_image(const std::filesystem::path& dir, const Camera& camera) {
    const auto path = io::find_image(dir, camera.name);
    const io::ImageRGB image = io::read_image_rgb(path, {0, 0, 0});
    if (image.width != camera.width || image.height != camera.height)
        throw InputError(path.string(), "subject mask is " + std::to_string(image.width) + "x" +
                                            std::to_string(image.height) + ", but camera '" + camera.name + "' is " +
                                            std::to_string(camera.width) + "x" + std::to_string(camera.height));
    std::vector<uint8_t> mask(size_t(image.width) * image.height);
    for (size_t p = 0; p < mask.size(); ++p)
        mask[p] = image.rgb[3 * p] + image.rgb[3 * p + 1] + image.rgb[3 * p + 2] > 1.5f;
    return mask;
}

// Sums of one comparison over the views; the subject's only over views that have subject pixels.
struct ScoreSums {
    SubjectScores sum;
    size_t views = 0, subject_views = 0;

    void add(const std::vector<float>& image, const std::vector<float>& target, const std::vector<uint8_t>& mask,
             int width, int height) {
        sum.psnr += eval::psnr(image.data(), target.data(), width, height);
        sum.ssim += eval::ssim(image.data(), target.data(), width, height);
        ++views;
        const double p = eval::masked_psnr(image.data(), target.data(), mask.data(), width, height);
        const double s = eval::masked_ssim(image.data(), target.data(), mask.data(), width, height);
        if (std::isnan(p) || std::isnan(s)) return;
        sum.subject_psnr += p;
        sum.subject_ssim += s;
        ++subject_views;
    }
    SubjectScores mean() const {
        SubjectScores m;
        m.psnr = sum.psnr / double(views);
        m.ssim = sum.ssim / double(views);
        m.subject_psnr = subject_views ? sum.subject_psnr / double(subject_views) : NAN;
        m.subject_ssim = subject_views ? sum.subject_ssim / double(subject_views) : NAN;
        return m;
    }
};

// The unpruned render with everything outside the subject region dimmed to a quarter.
std::vector<float> region_panel(const std::vector<float>& rgb, const std::vector<uint8_t>& mask) {
    std::vector<float> out = rgb;
    for (size_t p = 0; p < mask.size(); ++p)
        if (!mask[p])
            for (int c = 0; c < 3; ++c) out[3 * p + c] *= 0.25f;
    return out;
}

void write_sheet(const SubjectSheets& sheets, const std::string& stem, const RenderOutput& unpruned,
                 const RenderOutput& pruned, const std::vector<uint8_t>& mask, const std::vector<float>* photo) {
    const int w = pruned.width, h = pruned.height;
    std::vector<report::SheetPanel> panels;
    if (photo) panels.push_back({"photo", w, h, *photo});
    panels.push_back({"unpruned", w, h, unpruned.rgb});
    panels.push_back({"pruned", w, h, pruned.rgb});
    panels.push_back({"subject region", w, h, region_panel(unpruned.rgb, mask)});
    const std::vector<float>& target = photo ? *photo : unpruned.rgb;
    panels.push_back(report::heat_map_panel(pruned.rgb.data(), target.data(), w, h, sheets.max_error,
                                          photo ? "pruned vs photo" : "pruned vs unpruned"));
    std::filesystem::create_directories(sheets.dir);
    report::write_comparison_sheet(sheets.dir / (stem + "_subject.png"), panels, sheets.mode);
}

}  // namespace

SubjectSpec parse_subject_spec(const std::string& subject, const std::string& masks_dir) {
    SubjectSpec spec;
    if (!masks_dir.empty()) {
        if (!std::filesystem::is_directory(masks_dir)) throw InputError(masks_dir, "subject masks folder not found");
        spec.masks_dir = masks_dir;
        return spec;
    }
    if (!subject.empty() && subject != "auto") spec.ball = eval::parse_subject_ball(subject);
    return spec;
}

SubjectMasks subject_masks(const SubjectSpec& spec, const std::vector<Camera>& cameras, std::string* description) {
    if (spec.masks_dir) {
        if (description) *description = "masks in " + spec.masks_dir->string();
        return [dir = *spec.masks_dir](const Camera& camera, const RenderOutput&) { return mask_from_image(dir, camera); };
    }
    const eval::SubjectBall ball = spec.ball ? *spec.ball : eval::auto_subject_ball(cameras);
    if (description) {
        char text[160];
        std::snprintf(text, sizeof(text), "%s ball at (%.4g, %.4g, %.4g), radius %.4g", spec.ball ? "given" : "automatic",
                      ball.centre.x, ball.centre.y, ball.centre.z, ball.radius);
        *description = text;
    }
    return [ball](const Camera& camera, const RenderOutput& unpruned) { return eval::subject_mask(unpruned, camera, ball); };
}

SubjectQuality measure_subject_quality(Renderer& renderer, const GaussianCloud& unpruned, const GaussianCloud& pruned,
                                       const std::vector<Camera>& test_cameras,
                                       const std::optional<std::filesystem::path>& images_dir,
                                       const RenderSettings& settings, const SubjectMasks& masks,
                                       const std::optional<SubjectSheets>& sheets) {
    if (test_cameras.empty()) throw InputError("subject quality", "no test views");
    std::vector<RenderOutput> references;
    std::vector<std::vector<uint8_t>> regions;
    renderer.set_scene(unpruned);
    for (const Camera& camera : test_cameras) {
        references.push_back(renderer.render(camera, settings));
        regions.push_back(masks(camera, references.back()));
    }
    std::vector<std::vector<float>> photos;
    if (images_dir)
        for (const Camera& camera : test_cameras) {
            const auto path = io::find_image(*images_dir, camera.name);
            io::ImageRGB photo = io::read_image_rgb(path, settings.background);
            if (photo.width != camera.width || photo.height != camera.height)
                throw InputError(path.string(), "photo is not the size of camera '" + camera.name + "'");
            photos.push_back(std::move(photo.rgb));
        }

    const std::vector<std::string> stems = output_stems(test_cameras);
    SubjectQuality q;
    ScoreSums against_unpruned, before, after;
    renderer.set_scene(pruned);
    for (size_t v = 0; v < test_cameras.size(); ++v) {
        const RenderOutput image = renderer.render(test_cameras[v], settings);
        const RenderOutput& reference = references[v];
        const std::vector<uint8_t>& mask = regions[v];
        size_t inside = 0;
        for (uint8_t m : mask) inside += m != 0;
        q.subject_fraction += double(inside) / double(mask.size());
        q.views_without_subject += inside == 0;
        against_unpruned.add(image.rgb, reference.rgb, mask, image.width, image.height);
        if (sheets) write_sheet(*sheets, stems[v], reference, image, mask, photos.empty() ? nullptr : &photos[v]);
        if (photos.empty()) continue;
        before.add(reference.rgb, photos[v], mask, image.width, image.height);
        after.add(image.rgb, photos[v], mask, image.width, image.height);
    }
    q.subject_fraction /= double(test_cameras.size());
    q.pruned_vs_unpruned = against_unpruned.mean();
    if (!photos.empty()) {
        q.unpruned_vs_photos = before.mean();
        q.pruned_vs_photos = after.mean();
    }
    return q;
}

}  // namespace vksplat::jobs
