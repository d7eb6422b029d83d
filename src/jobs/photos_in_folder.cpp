// A PhotoSource over a folder of photos. Apart from finetune.cpp because it decodes images
// (OpenCV), which the GPU-host benchmarks built on the re-fit job do without.
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/jobs/finetune.hpp"

namespace vksplat::jobs {

PhotoSource photos_in_folder(const std::filesystem::path& images_dir, const std::array<float, 3>& background,
                             bool resize) {
    if (!std::filesystem::is_directory(images_dir))
        throw InputError(images_dir.string(), "is not a folder of photos");
    return [images_dir, background, resize](const Camera& camera) {
        io::ImageRGB image = io::read_image_rgb(io::find_image(images_dir, camera.name), background);
        if (!resize || (image.width == camera.width && image.height == camera.height)) return image;
        cv::Mat source(image.height, image.width, CV_32FC3, image.rgb.data()), resized;
        cv::resize(source, resized, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
        io::ImageRGB out{camera.width, camera.height, {}};
        out.rgb.assign(resized.ptr<float>(), resized.ptr<float>() + size_t(camera.width) * camera.height * 3);
        return out;
    };
}

}  // namespace vksplat::jobs
