#include "train/trainable_scene.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/command_stream.hpp"
#include "gpu/transfer.hpp"
#include "vksplat/error.hpp"

namespace vksplat::train {
namespace {

ParameterLayout layout_of(size_t count, int sh_degree) {
    return {static_cast<uint32_t>(count), static_cast<uint32_t>(sh_coefficients_for_degree(sh_degree))};
}

}  // namespace

std::vector<float> pack_parameters(const GaussianCloud& cloud) {
    const ParameterLayout layout = layout_of(cloud.size(), cloud.sh_degree);
    std::vector<float> packed(layout.total());
    std::copy(cloud.positions.begin(), cloud.positions.end(), packed.begin() + layout.positions());
    std::copy(cloud.log_scales.begin(), cloud.log_scales.end(), packed.begin() + layout.log_scales());
    std::copy(cloud.rotations.begin(), cloud.rotations.end(), packed.begin() + layout.rotations());
    std::copy(cloud.opacity_logits.begin(), cloud.opacity_logits.end(), packed.begin() + layout.opacities());
    std::copy(cloud.sh.begin(), cloud.sh.end(), packed.begin() + layout.sh());
    return packed;
}

GaussianCloud unpack_parameters(const std::vector<float>& packed, uint32_t count, int sh_degree) {
    const ParameterLayout layout = layout_of(count, sh_degree);
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(count);
    const auto copy = [&](uint64_t offset, std::vector<float>& out) {
        std::copy(packed.begin() + offset, packed.begin() + offset + out.size(), out.begin());
    };
    copy(layout.positions(), cloud.positions);
    copy(layout.log_scales(), cloud.log_scales);
    copy(layout.rotations(), cloud.rotations);
    copy(layout.opacities(), cloud.opacity_logits);
    copy(layout.sh(), cloud.sh);
    return cloud;
}

gpu::Buffer TrainableScene::allocate_array(const gpu::Context& context, const ParameterLayout& layout,
                                           const char* name) {
    // Buffers are never empty: a scene pruned to nothing still has somewhere to point.
    return gpu::Buffer(context, std::max<uint64_t>(layout.total(), 1) * sizeof(float), gpu::MemoryKind::device, name);
}

void TrainableScene::allocate_gradients(const gpu::Context& context) {
    grads = allocate_array(context, layout, "parameter gradients");
}

void TrainableScene::allocate_sums(const gpu::Context& context) {
    densify = gpu::Buffer(context, std::max<uint64_t>(layout.count, 1) * kDensifyStride * sizeof(float),
                          gpu::MemoryKind::device, "densification sums");
    gpu::CommandStream stream(context, 0);
    stream.begin();
    stream.fill(densify, 0);
    stream.submit_and_wait();
}

TrainableScene TrainableScene::allocate(const gpu::Context& context, uint32_t count, int sh_degree) {
    TrainableScene scene;
    scene.layout = layout_of(count, sh_degree);
    scene.sh_degree = sh_degree;
    scene.params = allocate_array(context, scene.layout, "trained parameters");
    scene.first_moment = allocate_array(context, scene.layout, "Adam first moments");
    scene.second_moment = allocate_array(context, scene.layout, "Adam second moments");
    scene.allocate_sums(context);
    return scene;
}

TrainableScene TrainableScene::upload(const gpu::Context& context, const GaussianCloud& cloud,
                                      const GaussianCloud* first_moment, const GaussianCloud* second_moment) {
    cloud.check_consistent();
    if (cloud.empty()) throw InputError("scene", "has no Gaussians to train");
    if (cloud.size() * layout_of(1, cloud.sh_degree).floats_per_gaussian() > std::numeric_limits<uint32_t>::max())
        throw InputError("scene", "has too many Gaussians to train (its parameters need 32-bit indices)");
    TrainableScene scene = allocate(context, uint32_t(cloud.size()), cloud.sh_degree);
    const auto fill = [&](const gpu::Buffer& destination, const GaussianCloud* values) {
        gpu::CommandStream stream(context, 0);
        stream.begin();
        if (!values) {
            stream.fill(destination, 0);
            stream.submit_and_wait();
            return;
        }
        const gpu::Buffer staged = gpu::upload_buffer(context, pack_parameters(*values), "trainer upload");
        stream.copy(staged, destination, staged.size());
        stream.submit_and_wait();
    };
    fill(scene.params, &cloud);
    fill(scene.first_moment, first_moment);
    fill(scene.second_moment, second_moment);
    return scene;
}

void TrainableScene::restore_densify_sums(const gpu::Context& context, const std::vector<float>& sums) const {
    if (sums.size() != uint64_t(layout.count) * kDensifyStride)
        throw std::invalid_argument("restore_densify_sums: " + std::to_string(sums.size()) + " sums for " +
                                    std::to_string(layout.count) + " Gaussians");
    const gpu::Buffer staged = gpu::upload_buffer(context, sums, "densification sums upload");
    gpu::CommandStream stream(context, 0);
    stream.begin();
    stream.copy(staged, densify, staged.size());
    stream.submit_and_wait();
}

GaussianCloud TrainableScene::download(const gpu::Context& context, const gpu::Buffer& buffer) const {
    return unpack_parameters(gpu::read_buffer<float>(context, buffer, layout.total()), layout.count, sh_degree);
}

}  // namespace vksplat::train
