// The photos of the test views, as the targets their renders are compared with.
#include <string>

#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/eval/quality.hpp"

namespace vksplat::eval {

TestViews photo_targets(const std::vector<Camera>& cameras, const std::filesystem::path& images_dir,
                        const std::array<float, 3>& background) {
    TestViews views;
    views.cameras = cameras;
    views.photos = true;
    for (const Camera& camera : cameras) {
        const std::filesystem::path path = io::find_image(images_dir, camera.name);
        io::ImageRGB photo = io::read_image_rgb(path, background);
        if (photo.width != camera.width || photo.height != camera.height)
            throw InputError(path.string(), "photo is " + std::to_string(photo.width) + "x" +
                                                std::to_string(photo.height) + " but camera '" + camera.name +
                                                "' renders " + std::to_string(camera.width) + "x" +
                                                std::to_string(camera.height));
        views.targets.push_back(std::move(photo.rgb));
    }
    return views;
}

}  // namespace vksplat::eval
