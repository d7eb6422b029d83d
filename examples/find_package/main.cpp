// The smallest program built against an installed vksplat: load a scene, render one view, save it.
//   render_scene SCENE OUT.png [WIDTH HEIGHT]
// Exits 1 if nothing was drawn, so a test can run it as a check.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <vksplat/scene/demo_scene.hpp>
#include <vksplat/io/formats.hpp>
#include <vksplat/io/image.hpp>
#include <vksplat/render/renderer.hpp>
#include <vksplat/version.hpp>

int main(int argc, char** argv) {
    if (argc != 3 && argc != 5) {
        std::fprintf(stderr, "usage: %s SCENE OUT.png [WIDTH HEIGHT]\n", argv[0]);
        return 2;
    }
    try {
        const int width = argc == 5 ? std::atoi(argv[3]) : 320;
        const int height = argc == 5 ? std::atoi(argv[4]) : 240;
        const vksplat::GaussianCloud cloud = vksplat::io::read_scene(argv[1]);

        vksplat::gpu::Context context;
        vksplat::Renderer renderer(context);
        renderer.set_scene(cloud);
        // One of the orbit cameras that frame the demo scene (radius 4, 30 degrees up).
        const vksplat::Camera camera = vksplat::make_orbit_cameras(1, width, height, 4.0, 30.0).front();
        const vksplat::RenderOutput image = renderer.render(camera);
        vksplat::io::write_png_rgb(argv[2], width, height, image.rgb.data(), 8, vksplat::io::WriteMode::overwrite);

        double coverage = 0;
        for (float a : image.alpha) coverage += a;
        coverage /= double(image.alpha.size());
        std::printf("vksplat %s: rendered %zu Gaussians on %s: %.1f%% of the image covered, wrote %s\n",
                    vksplat::kVersion, renderer.scene_size(), context.info().name.c_str(), coverage * 100, argv[2]);
        return coverage > 0.01 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
}
