#include "vksplat/train/gradients.hpp"

#include <cstring>
#include <stdexcept>

#include "gpu/command_stream.hpp"
#include "gpu/transfer.hpp"
#include "render/frame_layout.hpp"
#include "train/differentiable_renderer.hpp"
#include "train/trainable_scene.hpp"

namespace vksplat::train {

RenderGradients render_gradients(const gpu::Context& context, const GaussianCloud& cloud, const Camera& camera,
                                 const RenderSettings& settings, const std::vector<float>& weights,
                                 GradientSums sums, BlendBackward form) {
    camera.validate();
    const auto [pixels, tiles] = render::image_extent(camera);
    if (weights.size() != size_t(pixels) * 3)
        throw std::invalid_argument("render_gradients: " + std::to_string(weights.size()) + " weights for " +
                                    std::to_string(pixels) + " pixels (3 per pixel expected)");
    GaussianCloud checked = cloud;
    if (sanitize(checked).changed() > 0)
        throw std::invalid_argument("render_gradients: the cloud needs sanitising first (see sanitize())");

    TrainableScene scene = TrainableScene::upload(context, cloud);
    scene.allocate_gradients(context);
    DifferentiableRenderer renderer(context, sums, form);
    renderer.ensure(scene.layout.count, pixels, tiles);
    std::vector<float> pixel_weights(size_t(pixels) * 4, 0.0f);
    for (size_t p = 0; p < pixels; ++p) std::memcpy(&pixel_weights[4 * p], &weights[3 * p], 3 * sizeof(float));
    const gpu::Buffer pixel_grad = gpu::upload_buffer(context, pixel_weights, "pixel weights");

    renderer.backpropagate(scene, camera, settings, pixel_grad.address());

    RenderGradients out;
    out.gradient = scene.download(context, scene.grads);
    const auto color_alpha = gpu::read_buffer<float>(context, renderer.color_alpha(), size_t(pixels) * 4);
    out.image.width = camera.width;
    out.image.height = camera.height;
    out.image.rgb.resize(size_t(pixels) * 3);
    out.image.alpha.resize(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < 3; ++c) out.image.rgb[3 * p + c] = color_alpha[4 * p + c];
        out.image.alpha[p] = color_alpha[4 * p + 3];
    }
    return out;
}

}  // namespace vksplat::train
