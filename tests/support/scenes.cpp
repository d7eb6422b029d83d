#include "support/scenes.hpp"

#include <cmath>
#include <random>

#include "vksplat/reference/sh.hpp"

namespace vksplat::test {

std::vector<Camera> camera_ring(int count, glm::dvec3 target, double radius) {
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * M_PI * i / count;
        const glm::dvec3 eye =
            target + radius * glm::dvec3(std::sin(angle), 0.125 * std::cos(3.0 * angle), std::cos(angle));
        cameras.push_back(Camera::look_at(eye, target, {0, -1, 0}, 64, 48, 60.0, 50.0));
    }
    return cameras;
}

Camera forward_camera(int width, int height, double focal) {
    Camera camera;
    camera.name = "forward";
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = focal;
    camera.cx = width / 2.0;
    camera.cy = height / 2.0;
    return camera;
}

void add_splat(GaussianCloud& cloud, const Splat& s) {
    const size_t i = cloud.size();
    cloud.resize(i + 1);
    for (int k = 0; k < 3; ++k) {
        cloud.positions[i * 3 + k] = static_cast<float>(s.position[k]);
        cloud.log_scales[i * 3 + k] = static_cast<float>(std::log(s.scale[k]));
        // colour = C0 * dc + 0.5
        cloud.sh[i * size_t(cloud.sh_coefficients()) * 3 + k] = static_cast<float>((s.color[k] - 0.5) / reference::kShC0);
    }
    for (int k = 0; k < 4; ++k) cloud.rotations[i * 4 + k] = static_cast<float>(s.rotation[k]);
    cloud.opacity_logits[i] = static_cast<float>(std::log(s.opacity / (1.0 - s.opacity)));
}

glm::dvec3 at_pixel(const Camera& camera, double u, double v, double z) {
    return {(u + 0.5 - camera.cx) * z / camera.fx, (v + 0.5 - camera.cy) * z / camera.fy, z};
}

GaussianCloud random_scene(uint32_t seed, size_t n, int sh_degree, float z_near, float z_far, float scale_min,
                           float scale_max, float half_width) {
    std::mt19937 rng(seed);
    auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * float(rng() >> 8) * (1.0f / 16777216.0f); };
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(n);
    const int coeffs = cloud.sh_coefficients();
    for (size_t i = 0; i < n; ++i) {
        const float z = uniform(z_near, z_far);
        cloud.positions[3 * i + 0] = uniform(-half_width, half_width) * z / 4.0f;
        cloud.positions[3 * i + 1] = uniform(-half_width, half_width) * z / 4.0f;
        cloud.positions[3 * i + 2] = z;
        for (int k = 0; k < 3; ++k)
            cloud.log_scales[3 * i + k] = std::log(scale_min) + uniform(0, 1) * std::log(scale_max / scale_min);
        for (int k = 0; k < 4; ++k) cloud.rotations[4 * i + k] = uniform(-1, 1);
        cloud.rotations[4 * i] += 0.1f;  // keeps the norm away from zero
        cloud.opacity_logits[i] = uniform(-3, 4);
        for (int c = 0; c < coeffs * 3; ++c)
            cloud.sh[i * size_t(coeffs) * 3 + size_t(c)] = c < 3 ? uniform(-1.5f, 1.5f) : uniform(-0.4f, 0.4f);
    }
    return cloud;
}

std::vector<Camera> row_of_five_views() {
    std::vector<Camera> cameras;
    for (int i = 0; i < 5; ++i) {
        Camera camera = Camera::look_at({0.4 * (i - 2), 0.2 * (i % 2), 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 48, 40,
                                        45.0, 45.0);
        camera.name = "view_" + std::to_string(i);
        cameras.push_back(camera);
    }
    return cameras;
}

FisherScene fisher_scene() {
    FisherScene scene;
    scene.cameras = {forward_camera(40, 32, 40.0),
                     Camera::look_at({0.8, -0.3, 0.2}, {0.0, 0.0, 3.5}, {0.0, -1.0, 0.0}, 36, 36, 38.0, 38.0)};
    scene.cloud = random_scene(72, 10, 1, 2.5f, 5.0f, 0.08f, 0.5f, 1.2f);
    add_splat(scene.cloud,
              {.position = at_pixel(scene.cameras[0], 15, 18, 2.4), .scale = {0.3, 0.2, 0.25}, .opacity = 0.9999});
    add_splat(scene.cloud, {.position = {2.6, 0.1, 2.5}, .scale = {0.9, 0.6, 0.5}, .opacity = 0.8});
    scene.settings.background = {0.2f, 0.4f, 0.9f};
    return scene;
}

}  // namespace vksplat::test
