#pragma once
// The photos a job reads, made by rendering the scene they should reproduce: what the re-fit tests
// fit to. `renderer` (with its scene set) must outlive the source.
#include "vksplat/io/image.hpp"
#include "vksplat/jobs/finetune.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {

inline jobs::PhotoSource rendered_photos(Renderer& renderer) {
    return [&renderer](const Camera& camera) {
        const RenderOutput out = renderer.render(camera);
        return io::ImageRGB{out.width, out.height, out.rgb};
    };
}

}  // namespace vksplat::test
