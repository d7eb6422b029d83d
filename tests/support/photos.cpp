#include "support/photos.hpp"

#include "support/scenes.hpp"
#include "support/scratch_dir.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::test {

void write_renders_as_photos(Renderer& renderer, const std::vector<Camera>& cameras, const std::filesystem::path& folder,
                             int bit_depth) {
    std::filesystem::create_directories(folder);
    for (const Camera& camera : cameras) {
        const RenderOutput image = renderer.render(camera);
        io::write_png_rgb(folder / (camera.name + ".png"), image.width, image.height, image.rgb.data(), bit_depth);
    }
}

void PhotographedScene::SetUp() {
    dir = fresh_test_dir(prefix_);
    renderer = std::make_unique<Renderer>(context());
    cloud = random_scene(71, 500, 2, 3.0f, 8.0f, 0.01f, 0.3f, 1.5f);
    cameras = row_of_five_views();
    renderer->set_scene(cloud);
    write_renders_as_photos(*renderer, cameras, dir / "photos");
}

void PhotographedScene::TearDown() {
    std::filesystem::remove_all(dir);
    GpuTest::TearDown();
}

}  // namespace vksplat::test
