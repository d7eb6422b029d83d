#pragma once
// A generated scene (SH degree 1) and its renders through row_of_five_views() as training photos:
// the set-up of the tests that run the training loop on lavapipe.
#include <map>
#include <vector>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/train/trainer.hpp"

namespace vksplat::test {

class PhotographedViews : public GpuTest {
protected:
    // `gaussians` in the scene photographed.
    explicit PhotographedViews(size_t gaussians) : renderer(context()) {
        truth = random_scene(7, gaussians, 1, 4.0f, 6.0f, 0.05f, 0.2f, 1.0f);
        renderer.set_scene(truth);
        for (size_t v = 0; v < cameras.size(); ++v) {
            const RenderOutput out = renderer.render(cameras[v]);
            photos.emplace(v, train::Photo::from_image(io::ImageRGB{out.width, out.height, out.rgb}));
        }
    }
    Renderer renderer;
    GaussianCloud truth;
    std::vector<Camera> cameras = row_of_five_views();
    std::vector<size_t> views = {0, 1, 2, 3, 4};
    std::map<size_t, train::Photo> photos;
};

}  // namespace vksplat::test
