#include "frustum_splats.hpp"

#include <array>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace vksplat::viewer {
namespace {

constexpr double kShC0 = 0.28209479177387814;   // the DC term's basis constant
constexpr glm::dvec3 kColour{1.0, 0.85, 0.1};
constexpr int kSplatsPerEdge = 8;               // short enough to stay straight lines
constexpr float kOpacityLogit = 4.0f;           // sigmoid: 0.98

// One Gaussian stretched from a to b (half the segment's length as its standard deviation would
// blur the ends; a third keeps them near the segment).
void add_segment(GaussianCloud& cloud, const glm::dvec3& a, const glm::dvec3& b, double width) {
    const glm::dvec3 along = b - a;
    const double length = glm::length(along);
    if (!(length > 0)) return;
    const glm::dvec3 x = along / length;
    const glm::dvec3 helper = std::abs(x.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 y = glm::normalize(glm::cross(helper, x));
    const glm::dquat q = glm::quat_cast(glm::dmat3(x, y, glm::cross(x, y)));
    const size_t i = cloud.size();
    cloud.resize(i + 1);
    const glm::dvec3 mid = (a + b) * 0.5;
    for (int k = 0; k < 3; ++k) cloud.positions[3 * i + k] = float(mid[k]);
    const std::array<double, 3> scale{length / 3.0, width, width};
    for (int k = 0; k < 3; ++k) cloud.log_scales[3 * i + k] = float(std::log(scale[k]));
    const std::array<double, 4> rotation{q.w, q.x, q.y, q.z};
    for (int k = 0; k < 4; ++k) cloud.rotations[4 * i + k] = float(rotation[k]);
    cloud.opacity_logits[i] = kOpacityLogit;
    for (int c = 0; c < 3; ++c) cloud.sh[i * cloud.sh_coefficients() * 3 + c] = float((kColour[c] - 0.5) / kShC0);
}

}  // namespace

GaussianCloud frustum_splats(const std::vector<Camera>& cameras, double depth, double width, int sh_degree) {
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    for (const auto& camera : cameras) {
        const glm::dmat3 to_world = glm::transpose(camera.rotation);
        const glm::dvec3 centre = camera.centre();
        // The picture's corners at `depth`, through the pinhole (cx, cy and the focal lengths).
        std::array<glm::dvec3, 4> corner;
        const std::array<std::array<double, 2>, 4> pixels{
            {{0.0, 0.0}, {double(camera.width), 0.0}, {double(camera.width), double(camera.height)}, {0.0, double(camera.height)}}};
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 view((pixels[k][0] - camera.cx) / camera.fx * depth, (pixels[k][1] - camera.cy) / camera.fy * depth,
                                  depth);
            corner[k] = centre + to_world * view;
        }
        for (int k = 0; k < 4; ++k) {
            for (const auto& [a, b] : {std::pair{centre, corner[k]}, std::pair{corner[k], corner[(k + 1) % 4]}}) {
                for (int s = 0; s < kSplatsPerEdge; ++s)
                    add_segment(cloud, glm::mix(a, b, double(s) / kSplatsPerEdge),
                                glm::mix(a, b, double(s + 1) / kSplatsPerEdge), width);
            }
        }
    }
    return cloud;
}

}  // namespace vksplat::viewer
