#pragma once
// Photos for tests that measure against photos: a scene's own renders written as PNGs named after
// the cameras, so that the unpruned scene scores about 50 dB against them (8 bits) or more (16).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "support/gpu_fixture.hpp"

#include "vksplat/camera/camera.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {

// Renders every camera with the renderer's scene into `folder` (made if missing) as `<name>.png`.
void write_renders_as_photos(Renderer& renderer, const std::vector<Camera>& cameras,
                             const std::filesystem::path& folder, int bit_depth = 8);

// A small scene (500 Gaussians, SH degree 2) photographed by row_of_five_views() into
// dir / "photos" in 8 bits: the set-up of the tests that prune, re-fit and sweep against photos.
class PhotographedScene : public GpuTest {
protected:
    // `prefix` names the test's scratch folder (fresh_test_dir).
    explicit PhotographedScene(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override;
    void TearDown() override;

    std::filesystem::path dir;
    std::unique_ptr<Renderer> renderer;
    GaussianCloud cloud;
    std::vector<Camera> cameras;

private:
    std::string prefix_;
};

}  // namespace vksplat::test
