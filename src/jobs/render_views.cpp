#include "vksplat/jobs/render_views.hpp"

#include <cstdio>
#include <set>

#include "vksplat/io/output_folders.hpp"
#include "vksplat/error.hpp"
#include "vksplat/eval/metrics.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::jobs {
namespace {

namespace fs = std::filesystem;

// The files of one view: alpha and depth empty where not asked for, photo without images_dir.
struct ViewFiles {
    fs::path image, alpha, depth, photo;
};

std::string format_metric(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.4f", value);
    return text;
}

void write_metrics_csv(const fs::path& path, const RenderViewsResult& result, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out << "view,name,psnr,ssim\n";
        for (const auto& v : result.views)
            out << v.index << ',' << v.name << ',' << format_metric(v.psnr) << ',' << format_metric(v.ssim) << '\n';
        out << "mean,," << format_metric(result.mean_psnr) << ',' << format_metric(result.mean_ssim) << '\n';
    });
}

void refuse_other_size(const fs::path& photo_path, int width, int height, const Camera& camera) {
    if (width != camera.width || height != camera.height)
        throw InputError(photo_path.string(), "photo is " + std::to_string(width) + "x" + std::to_string(height) +
                                                  " but camera '" + camera.name + "' renders " +
                                                  std::to_string(camera.width) + "x" + std::to_string(camera.height));
}

// PNG and JPEG photos are measured from their headers before the first render, so that a photo of
// the wrong size is refused before any view is written; other formats are checked when decoded.
void check_photo_size_early(const fs::path& photo_path, const Camera& camera) {
    if (const auto size = io::header_image_size(photo_path))
        refuse_other_size(photo_path, (*size)[0], (*size)[1], camera);
}

void score_against_photo(ViewResult& view, const RenderOutput& image, const Camera& camera,
                         const fs::path& photo_path, const RenderSettings& settings) {
    const io::ImageRGB photo = io::read_image_rgb(photo_path, settings.background);
    refuse_other_size(photo_path, photo.width, photo.height, camera);
    view.psnr = eval::psnr(image.rgb.data(), photo.rgb.data(), image.width, image.height);
    view.ssim = eval::ssim(image.rgb.data(), photo.rgb.data(), image.width, image.height);
}

}  // namespace

std::vector<std::string> output_stems(const std::vector<Camera>& cameras) {
    std::vector<std::string> stems;
    for (size_t i = 0; i < cameras.size(); ++i) {
        char unnamed[32];
        std::snprintf(unnamed, sizeof(unnamed), "view_%04zu", i);
        stems.push_back(cameras[i].name.empty() ? unnamed : fs::path(cameras[i].name).stem().string());
    }
    // Plain stems first, so that no "-2" takes the name another camera has by itself.
    std::set<std::string> taken(stems.begin(), stems.end());
    std::set<std::string> given;
    for (std::string& stem : stems) {
        if (given.insert(stem).second) continue;
        std::string copy;
        for (int number = 2; taken.count(copy = stem + '-' + std::to_string(number)); ++number) {}
        stem = copy;
        taken.insert(stem);
        given.insert(stem);
    }
    return stems;
}

RenderViewsResult render_views(Renderer& renderer, const std::vector<Camera>& cameras,
                               const RenderViewsOptions& options, const Progress& progress) {
    if (options.bit_depth != 8 && options.bit_depth != 16)
        throw InputError("--bit-depth", "must be 8 or 16, not " + std::to_string(options.bit_depth));
    std::vector<size_t> views = options.views;
    if (views.empty())
        for (size_t i = 0; i < cameras.size(); ++i) views.push_back(i);
    check_view_indices(views, cameras.size());
    std::set<size_t> named;
    for (size_t view : views)
        if (!named.insert(view).second)
            throw InputError("view " + std::to_string(view), "is named twice; each view is rendered once");

    // Every file and photo, known and checked before the first render.
    const std::vector<std::string> stems = output_stems(cameras);
    std::vector<ViewFiles> files;
    std::vector<fs::path> inputs = options.inputs;
    for (size_t index : views) {
        ViewFiles view;
        const fs::path stem = options.out_dir / stems[index];
        view.image = fs::path(stem) += ".png";
        if (options.write_alpha) view.alpha = fs::path(stem) += ".alpha.png";
        if (options.write_depth) view.depth = fs::path(stem) += ".depth.npy";
        if (options.images_dir) {
            inputs.push_back(view.photo = io::find_image(*options.images_dir, cameras[index].name));
            check_photo_size_early(view.photo, cameras[index]);
        }
        files.push_back(view);
    }
    const fs::path metrics_csv = options.out_dir / "metrics.csv";
    io::OutputFolders folders;
    folders.create(options.out_dir);
    std::set<fs::path> outputs;
    const auto check = [&](const fs::path& path) {
        if (path.empty()) return;
        if (!outputs.insert(path).second)
            throw InputError(path.string(), "would be written twice: the cameras' names give two files this name");
        // Every input exists (it was read or found), so only an existing output can be one; skipping
        // the others saves seconds of path comparisons over hundreds of views.
        if (fs::exists(path)) io::refuse_input_as_output(path, inputs);
        io::check_writable(path, options.mode);
    };
    for (const ViewFiles& view : files)
        for (const fs::path* path : {&view.image, &view.alpha, &view.depth}) check(*path);
    if (options.images_dir) check(metrics_csv);

    RenderViewsResult result;
    result.has_metrics = options.images_dir.has_value();
    for (size_t done = 0; done < views.size(); ++done) {
        const size_t index = views[done];
        const Camera& camera = cameras[index];
        const ViewFiles& out = files[done];
        const RenderOutput image = renderer.render(camera, options.settings);

        ViewResult view;
        view.index = index;
        view.name = stems[index];
        view.gpu_milliseconds = renderer.last_frame().gpu_milliseconds;
        view.image = out.image;
        io::write_png_rgb(out.image, image.width, image.height, image.rgb.data(), options.bit_depth, options.mode);
        result.files.push_back(out.image);
        if (!out.alpha.empty()) {
            io::write_png_gray16(out.alpha, image.width, image.height, image.alpha.data(), options.mode);
            result.files.push_back(out.alpha);
        }
        if (!out.depth.empty()) {
            io::write_npy(out.depth, image.depth.data(), {size_t(image.height), size_t(image.width)}, options.mode);
            result.files.push_back(out.depth);
        }
        if (options.images_dir) score_against_photo(view, image, camera, out.photo, options.settings);
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
        result.metrics_csv = metrics_csv;
        write_metrics_csv(result.metrics_csv, result, options.mode);
        result.files.push_back(result.metrics_csv);
    }
    return result;
}

}  // namespace vksplat::jobs
