#include "vksplat/jobs/render_views.hpp"

#include <cstdio>
#include <sstream>

#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::jobs {
namespace {

std::string format_metric(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.4f", value);
    return text;
}

void write_metrics_csv(const std::filesystem::path& path, const RenderViewsResult& result, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out << "view,name,psnr,ssim\n";
        for (const auto& v : result.views)
            out << v.index << ',' << v.name << ',' << format_metric(v.psnr) << ',' << format_metric(v.ssim) << '\n';
        out << "mean,," << format_metric(result.mean_psnr) << ',' << format_metric(result.mean_ssim) << '\n';
    });
}

void score_against_photo(ViewResult& view, const RenderOutput& image, const Camera& camera,
                         const std::filesystem::path& images_dir, const RenderSettings& settings) {
    const auto photo_path = io::find_image(images_dir, camera.name);
    const io::ImageRGB photo = io::read_image_rgb(photo_path, settings.background);
    if (photo.width != image.width || photo.height != image.height)
        throw InputError(photo_path.string(), "photo is " + std::to_string(photo.width) + "x" +
                                                  std::to_string(photo.height) + " but camera '" + camera.name +
                                                  "' renders " + std::to_string(image.width) + "x" +
                                                  std::to_string(image.height));
    view.psnr = eval::psnr(image.rgb.data(), photo.rgb.data(), image.width, image.height);
    view.ssim = eval::ssim(image.rgb.data(), photo.rgb.data(), image.width, image.height);
}

}  // namespace

std::string output_stem(const Camera& camera, size_t index) {
    if (camera.name.empty()) {
        char text[32];
        std::snprintf(text, sizeof(text), "view_%04zu", index);
        return text;
    }
    return std::filesystem::path(camera.name).stem().string();
}

RenderViewsResult render_views(Renderer& renderer, const std::vector<Camera>& cameras,
                               const RenderViewsOptions& options, const Progress& progress) {
    if (options.bit_depth != 8 && options.bit_depth != 16)
        throw InputError("--bit-depth", "must be 8 or 16, not " + std::to_string(options.bit_depth));
    std::vector<size_t> views = options.views;
    if (views.empty())
        for (size_t i = 0; i < cameras.size(); ++i) views.push_back(i);
    std::filesystem::create_directories(options.out_dir);

    RenderViewsResult result;
    result.has_metrics = options.images_dir.has_value();
    for (size_t done = 0; done < views.size(); ++done) {
        const size_t index = views[done];
        if (index >= cameras.size())
            throw InputError("view " + std::to_string(index), "there are only " + std::to_string(cameras.size()) +
                                                                  " cameras");
        const Camera& camera = cameras[index];
        const RenderOutput image = renderer.render(camera, options.settings);

        ViewResult view;
        view.index = index;
        view.name = output_stem(camera, index);
        view.gpu_milliseconds = renderer.last_frame().gpu_milliseconds;
        view.image = options.out_dir / (view.name + ".png");
        io::write_png_rgb(view.image, image.width, image.height, image.rgb.data(), options.bit_depth, options.mode);
        if (options.write_alpha)
            io::write_png_gray16(options.out_dir / (view.name + ".alpha.png"), image.width, image.height,
                                 image.alpha.data(), options.mode);
        if (options.write_depth)
            io::write_npy(options.out_dir / (view.name + ".depth.npy"), image.depth.data(),
                          {size_t(image.height), size_t(image.width)}, options.mode);
        if (options.images_dir) score_against_photo(view, image, camera, *options.images_dir, options.settings);
        result.views.push_back(view);
        if (progress) progress(done + 1, views.size());
    }
    if (result.has_metrics && !result.views.empty()) {
        for (const auto& v : result.views) {
            result.mean_psnr += v.psnr;
            result.mean_ssim += v.ssim;
        }
        result.mean_psnr /= double(result.views.size());
        result.mean_ssim /= double(result.views.size());
        result.metrics_csv = options.out_dir / "metrics.csv";
        write_metrics_csv(result.metrics_csv, result, options.mode);
    }
    return result;
}

}  // namespace vksplat::jobs
