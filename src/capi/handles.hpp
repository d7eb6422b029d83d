#pragma once
// What the C API's opaque handles hold: the C++ objects themselves, nothing more.
#include "vksplat/gpu/context.hpp"
#include "vksplat/render/renderer.hpp"
#include "vksplat/scene/scene.hpp"
#include "vksplat/vksplat.h"

struct vksplat_context {
    template <typename Options>
    explicit vksplat_context(const Options& options) : context(options) {}
    vksplat::gpu::Context context;
};

struct vksplat_scene {
    vksplat::GaussianCloud cloud;
};

struct vksplat_renderer {
    explicit vksplat_renderer(const vksplat::gpu::Context& context) : renderer(context) {}
    vksplat::Renderer renderer;
};
