#include "jobs/training_setup.hpp"

#include "vksplat/train/scene_extent.hpp"

namespace vksplat::jobs {

std::map<size_t, train::Photo> training_photos(const PhotoSource& photos, const std::vector<Camera>& cameras,
                                               const std::vector<size_t>& views, const LossMasks& masks) {
    std::map<size_t, train::Photo> out;
    for (size_t view : views)
        out.emplace(view, training_photo(photos, cameras[view], masks ? masks(view) : std::vector<uint8_t>{}));
    return out;
}

double training_extent(const std::vector<Camera>& cameras, const std::vector<size_t>& views, const Notice& notice) {
    std::vector<Camera> train_cameras;
    for (size_t view : views) train_cameras.push_back(cameras[view]);
    const train::SceneExtent extent = train::scene_extent(train_cameras);
    for (size_t i : extent.distrusted)
        if (notice)
            notice("warning: camera '" + cameras[views[i]].name + "' lies far from the others; left out of the scene extent");
    return extent.radius;
}

}  // namespace vksplat::jobs
