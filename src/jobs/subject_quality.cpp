// Whole-picture and subject-region quality of a pruned scene (see subject_quality.hpp).
#include "vksplat/jobs/subject_quality.hpp"

#include <cmath>
#include <limits>

#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::jobs {
namespace {

struct Box {
    int x0, y0, x1, y1;  // [x0, x1) x [y0, y1)
};

Box central_box(int width, int height) { return {width / 6, height / 6, width - width / 6, height - height / 6}; }

std::vector<uint8_t> subject_mask(const RenderOutput& unpruned) {
    const Box box = central_box(unpruned.width, unpruned.height);
    std::vector<uint8_t> mask(unpruned.alpha.size(), 0);
    for (int y = box.y0; y < box.y1; ++y)
        for (int x = box.x0; x < box.x1; ++x) {
            const size_t p = size_t(y) * unpruned.width + x;
            mask[p] = unpruned.alpha[p] > 0.5f;
        }
    return mask;
}

double masked_psnr(const std::vector<float>& a, const std::vector<float>& b, const std::vector<uint8_t>& mask) {
    double squared = 0;
    size_t count = 0;
    for (size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = std::clamp(a[p * 3 + c], 0.0f, 1.0f) - std::clamp(b[p * 3 + c], 0.0f, 1.0f);
            squared += d * d;
            ++count;
        }
    }
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    const double mse = squared / double(count);
    return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

std::vector<float> crop(const std::vector<float>& rgb, int width, const Box& box) {
    std::vector<float> out;
    out.reserve(size_t(box.x1 - box.x0) * size_t(box.y1 - box.y0) * 3);
    for (int y = box.y0; y < box.y1; ++y)
        out.insert(out.end(), rgb.begin() + (size_t(y) * width + box.x0) * 3, rgb.begin() + (size_t(y) * width + box.x1) * 3);
    return out;
}

void add(SubjectScores& sum, const std::vector<float>& image, const std::vector<float>& target,
         const std::vector<uint8_t>& mask, int width, int height) {
    const Box box = central_box(width, height);
    sum.psnr += eval::psnr(image.data(), target.data(), width, height);
    sum.ssim += eval::ssim(image.data(), target.data(), width, height);
    sum.subject_psnr += masked_psnr(image, target, mask);
    sum.subject_ssim += eval::ssim(crop(image, width, box).data(), crop(target, width, box).data(), box.x1 - box.x0,
                                   box.y1 - box.y0);
}

void divide(SubjectScores& s, double n) {
    s.psnr /= n;
    s.ssim /= n;
    s.subject_psnr /= n;
    s.subject_ssim /= n;
}

}  // namespace

SubjectQuality measure_subject_quality(Renderer& renderer, const GaussianCloud& unpruned, const GaussianCloud& pruned,
                                       const std::vector<Camera>& test_cameras,
                                       const std::optional<std::filesystem::path>& images_dir,
                                       const RenderSettings& settings) {
    if (test_cameras.empty()) throw InputError("subject quality", "no test views");
    std::vector<RenderOutput> references;
    renderer.set_scene(unpruned);
    for (const Camera& camera : test_cameras) references.push_back(renderer.render(camera, settings));
    std::vector<std::vector<float>> photos;
    if (images_dir)
        for (const Camera& camera : test_cameras) {
            const auto path = io::find_image(*images_dir, camera.name);
            io::ImageRGB photo = io::read_image_rgb(path, settings.background);
            if (photo.width != camera.width || photo.height != camera.height)
                throw InputError(path.string(), "photo is not the size of camera '" + camera.name + "'");
            photos.push_back(std::move(photo.rgb));
        }

    SubjectQuality q;
    SubjectScores before, after_photo;
    renderer.set_scene(pruned);
    for (size_t v = 0; v < test_cameras.size(); ++v) {
        const RenderOutput image = renderer.render(test_cameras[v], settings);
        const RenderOutput& reference = references[v];
        const std::vector<uint8_t> mask = subject_mask(reference);
        size_t inside = 0;
        for (uint8_t m : mask) inside += m;
        q.subject_fraction += double(inside) / double(mask.size());
        add(q.pruned_vs_unpruned, image.rgb, reference.rgb, mask, image.width, image.height);
        if (photos.empty()) continue;
        add(before, reference.rgb, photos[v], mask, image.width, image.height);
        add(after_photo, image.rgb, photos[v], mask, image.width, image.height);
    }
    const double n = double(test_cameras.size());
    q.subject_fraction /= n;
    divide(q.pruned_vs_unpruned, n);
    if (!photos.empty()) {
        divide(before, n);
        divide(after_photo, n);
        q.unpruned_vs_photos = before;
        q.pruned_vs_photos = after_photo;
    }
    return q;
}

}  // namespace vksplat::jobs
