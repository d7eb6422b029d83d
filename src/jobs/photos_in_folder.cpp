// A PhotoSource over a folder of photos. Apart from finetune.cpp because it decodes images
// (OpenCV), which the GPU-host benchmarks built on the re-fit job do without.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/jobs/finetune.hpp"

namespace vksplat::jobs {

PhotoSource photos_in_folder(const std::filesystem::path& images_dir, const std::array<float, 3>& background,
                             double resolution_scale, io::PhotoUndistortion undistortion) {
    if (!std::filesystem::is_directory(images_dir))
        throw InputError(images_dir.string(), "is not a folder of photos");
    return [images_dir, background, resolution_scale, undistortion](const Camera& camera) {
        const std::filesystem::path file = io::find_image(images_dir, camera.name);
        io::ImageRGB image = undistortion.apply(camera.name, io::read_image_rgb(file, background), file);
        if (resolution_scale == 1.0) return image;  // checked_photo compares the sizes
        // The size is checked before resizing, as load_training_data scaled the camera: a photo of
        // another shape would otherwise be stretched to fit and trained on, distorted.
        const auto scaled = [&](int size) { return std::max(1, int(std::lround(size * resolution_scale))); };
        if (scaled(image.width) != camera.width || scaled(image.height) != camera.height) {
            std::ostringstream message;
            message << "is " << image.width << 'x' << image.height << ", which a resolution scale of "
                    << resolution_scale << " makes " << scaled(image.width) << 'x' << scaled(image.height)
                    << ", but camera '" << camera.name << "' is " << camera.width << 'x' << camera.height
                    << " at that scale";
            throw InputError(file.string(), message.str());
        }
        cv::Mat source(image.height, image.width, CV_32FC3, image.rgb.data()), resized;
        cv::resize(source, resized, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
        io::ImageRGB out{camera.width, camera.height, {}};
        out.rgb.assign(resized.ptr<float>(), resized.ptr<float>() + size_t(camera.width) * camera.height * 3);
        return out;
    };
}

}  // namespace vksplat::jobs
