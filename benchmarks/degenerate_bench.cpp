// degenerate_bench: GPU time per frame on generated scenes at the edges of the pipeline, to show
// that none of them makes the renderer blow up (tests/render/degenerate_scenes_test.cpp checks
// their pictures against the reference on small versions; this one is for sizes the reference
// cannot follow, e.g. a million Gaussians on one 16x16 tile). For a GPU: on lavapipe a shader
// invocation's loops stop after 65535 iterations in all, which cuts the one-tile blend short.
// Usage: degenerate_bench [--count 1000000] [--size 1920x1080] [--reps 20] [--device NAME]
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "vksplat/error.hpp"
#include "vksplat/bench/benchmark.hpp"

namespace {

using namespace vksplat;

constexpr double kShC0 = 0.28209479177387814;

void add(GaussianCloud& cloud, const glm::dvec3& position, const glm::dvec3& scale, double opacity,
         const glm::dvec3& colour) {
    const size_t i = cloud.size();
    cloud.resize(i + 1);
    for (int k = 0; k < 3; ++k) {
        cloud.positions[i * 3 + k] = float(position[k]);
        cloud.log_scales[i * 3 + k] = float(std::log(scale[k]));
        cloud.sh[i * cloud.sh_coefficients() * 3 + k] = float((colour[k] - 0.5) / kShC0);
    }
    cloud.rotations[i * 4] = 1.0f;
    cloud.opacity_logits[i] = float(std::log(opacity / (1.0 - opacity)));
}

struct Case {
    const char* name;
    std::function<GaussianCloud(size_t count, const Camera& camera)> make;
};

// Where a point at view depth z lands on pixel (u, v) of a camera at the origin looking down +z.
glm::dvec3 at_pixel(const Camera& camera, double u, double v, double z) {
    return {(u - camera.cx) / camera.fx * z, (v - camera.cy) / camera.fy * z, z};
}

// `count` Gaussians whose centres land in the pixel rectangle [u0, u1) x [v0, v1) of `camera`, at
// depths 2 to 10 (or all at 5), with log-uniform scales, then moved by `offset` (the camera moves too).
GaussianCloud spread(size_t count, const Camera& camera, uint32_t seed, const glm::dvec4& rect,
                     const glm::dvec3& offset, double scale_min, double scale_max, bool one_depth) {
    GaussianCloud cloud;
    cloud.positions.reserve(count * 3);
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> zero_one(0.0, 1.0);
    for (size_t i = 0; i < count; ++i) {
        const double z = one_depth ? 5.0 : 2.0 + 8.0 * zero_one(random);
        const double log_scale = std::log(scale_min) + (std::log(scale_max) - std::log(scale_min)) * zero_one(random);
        const double u = rect[0] + (rect[2] - rect[0]) * zero_one(random);
        const double v = rect[1] + (rect[3] - rect[1]) * zero_one(random);
        add(cloud, offset + at_pixel(camera, u, v, z),
            glm::dvec3(std::exp(log_scale)), 0.05 + 0.5 * zero_one(random),
            {zero_one(random), zero_one(random), zero_one(random)});
    }
    return cloud;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"degenerate_bench: GPU time per frame on degenerate generated scenes"};
    size_t count = 1000000;
    std::string size_text = "1280x720", device;
    int reps = 20;
    app.add_option("--count", count, "Gaussians per scene");
    app.add_option("--size", size_text, "WxH");
    app.add_option("--reps", reps);
    app.add_option("--device", device);
    CLI11_PARSE(app, argc, argv);
    try {
        Camera camera;
        if (std::sscanf(size_text.c_str(), "%dx%d", &camera.width, &camera.height) != 2)
            throw InputError("--size", "expected WxH");
        camera.fx = camera.fy = 0.8 * camera.width;
        camera.cx = camera.width / 2.0;
        camera.cy = camera.height / 2.0;
        const glm::dvec3 far_offset{1e6, -1e6, 1e6};
        const glm::dvec4 image{0, 0, camera.width, camera.height};
        const glm::dvec4 first_tile{1, 1, 15, 15};
        const std::vector<Case> cases = {
            {"ordinary", [&](size_t n, const Camera& c) { return spread(n, c, 1, image, {}, 0.005, 0.05, false); }},
            {"one_tile", [&](size_t n, const Camera& c) { return spread(n, c, 2, first_tile, {}, 0.001, 0.004, false); }},
            {"one_depth", [&](size_t n, const Camera& c) { return spread(n, c, 3, image, {}, 0.005, 0.05, true); }},
            {"scales_1e-10_to_1e10",
             [&](size_t n, const Camera& c) { return spread(n, c, 4, image, {}, 1e-10, 1e10, false); }},
            {"far_from_origin_1e6",
             [&](size_t n, const Camera& c) { return spread(n, c, 5, image, far_offset, 0.005, 0.05, false); }},
        };

        gpu::Context context({device, false});
        Renderer renderer(context);
        std::printf("device: %s, %zu Gaussians per scene, %dx%d\n", context.info().name.c_str(), count, camera.width,
                    camera.height);
        std::printf("%-22s %12s %12s %10s %12s\n", "scene", "median ms", "min ms", "visible", "tile entries");
        for (const auto& c : cases) {
            Camera view = camera;
            if (std::string(c.name) == "far_from_origin_1e6") {
                view.translation = -far_offset;  // identity rotation: translation = -centre
            }
            // A case the renderer refuses (a million huge splats need more tile entries than one
            // frame can sort) is a result for the table, not the end of the run.
            try {
                renderer.set_scene(c.make(count, camera));
                bench::BenchmarkOptions options;
                options.repetitions = reps;
                options.warmup = 2;
                const auto result = bench::benchmark_views(renderer, {view}, {0}, options, context.info().name);
                const auto& v = result.views[0];
                std::printf("%-22s %12.3f %12.3f %10u %12u\n", c.name, v.median_ms, v.min_ms, v.visible,
                            v.tile_entries);
            } catch (const GpuError& e) {
                std::printf("%-22s refused: %s\n", c.name, e.what());
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "degenerate_bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
