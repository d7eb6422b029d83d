#include "support/photos.hpp"

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

}  // namespace vksplat::test
