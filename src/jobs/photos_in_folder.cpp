// A PhotoSource over a folder of photos. Apart from finetune.cpp because it decodes images
// (OpenCV), which the GPU-host benchmarks built on the re-fit job do without.
#include <filesystem>

#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/jobs/finetune.hpp"

namespace vksplat::jobs {

PhotoSource photos_in_folder(const std::filesystem::path& images_dir, const std::array<float, 3>& background) {
    if (!std::filesystem::is_directory(images_dir))
        throw InputError(images_dir.string(), "is not a folder of photos");
    return [images_dir, background](const Camera& camera) {
        return io::read_image_rgb(io::find_image(images_dir, camera.name), background);
    };
}

}  // namespace vksplat::jobs
