#pragma once
// TrainableScene: a scene's raw parameters on the device in the trainer's layout
// (parameter_layout.hpp), with Adam's two moments laid out the same, and their gradients where a
// caller reads them (a training step hands each gradient to Adam as it finds it and keeps none).
#include <cstdint>
#include <vector>

#include "gpu/buffer.hpp"
#include "train/parameter_layout.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::train {

struct TrainableScene {
    ParameterLayout layout;
    int sh_degree = 0;
    gpu::Buffer params, first_moment, second_moment;
    gpu::Buffer grads;    // empty unless allocate_gradients() was called
    gpu::Buffer densify;  // kDensifyStride floats per Gaussian, summed by preprocess_backward

    // Uploads a consistent cloud (the caller sanitises it); the moments (unless given, in the
    // cloud's layout) and the densification sums start at zero.
    static TrainableScene upload(const gpu::Context& context, const GaussianCloud& cloud,
                                 const GaussianCloud* first_moment = nullptr, const GaussianCloud* second_moment = nullptr);
    // Room for `count` Gaussians: parameters and moments uninitialised, densification sums zero.
    static TrainableScene allocate(const gpu::Context& context, uint32_t count, int sh_degree);
    // One array of `layout` (parameters, gradients or a moment), uninitialised.
    static gpu::Buffer allocate_array(const gpu::Context& context, const ParameterLayout& layout, const char* name);
    // Densification sums for the current layout, zero.
    void allocate_sums(const gpu::Context& context);
    // An array for the gradients, for backward passes whose caller reads them (not training).
    void allocate_gradients(const gpu::Context& context);
    // Densification sums saved with a checkpoint (kDensifyStride floats per Gaussian) back on
    // the device, so that a resumed run densifies as the uninterrupted one would.
    void restore_densify_sums(const gpu::Context& context, const std::vector<float>& sums) const;
    // The parameters (or any buffer of this layout) as a cloud.
    GaussianCloud download(const gpu::Context& context, const gpu::Buffer& buffer) const;
    GaussianCloud download(const gpu::Context& context) const { return download(context, params); }
    uint64_t device_bytes() const {
        return params.size() + first_moment.size() + second_moment.size() + grads.size() + densify.size();
    }
    VkDeviceAddress sh_address() const { return params.address() + layout.sh() * sizeof(float); }
};

// The cloud's arrays in the trainer's layout, and back.
std::vector<float> pack_parameters(const GaussianCloud& cloud);
GaussianCloud unpack_parameters(const std::vector<float>& packed, uint32_t count, int sh_degree);

}  // namespace vksplat::train
