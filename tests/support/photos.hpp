#pragma once
// Photos for tests that measure against photos: a scene's own renders written as PNGs named after
// the cameras, so that the unpruned scene scores about 50 dB against them (8 bits) or more (16).
#include <filesystem>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {

// Renders every camera with the renderer's scene into `folder` (made if missing) as `<name>.png`.
void write_renders_as_photos(Renderer& renderer, const std::vector<Camera>& cameras,
                             const std::filesystem::path& folder, int bit_depth = 8);

}  // namespace vksplat::test
