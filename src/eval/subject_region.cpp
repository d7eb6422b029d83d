// The subject ball and its per-view pixel mask (see subject_region.hpp).
#include "vksplat/eval/subject_region.hpp"

#include <cmath>
#include <sstream>

#include "vksplat/camera/camera_focus.hpp"
#include "vksplat/error.hpp"
#include "stats/median.hpp"

namespace vksplat::eval {

SubjectBall auto_subject_ball(const std::vector<Camera>& cameras) {
    const auto focus = common_focus(cameras);
    if (!focus)
        throw InputError("--subject auto", "the cameras have no common focus (their axes are nearly parallel); give the "
                                           "subject as --subject x,y,z,r or --subject-masks DIR");
    std::vector<double> distances;
    for (const Camera& camera : cameras) distances.push_back(glm::length(camera.centre() - *focus));
    return {*focus, 0.3 * stats::median(std::move(distances))};
}

SubjectBall parse_subject_ball(const std::string& text) {
    std::istringstream in(text);
    double v[4];
    char comma = ',';
    for (int k = 0; k < 4; ++k)
        if ((k > 0 && !(in >> comma)) || comma != ',' || !(in >> v[k]) || !std::isfinite(v[k]))
            throw InputError("--subject " + text, "expected auto or x,y,z,r (four numbers)");
    std::string rest;
    if (in >> rest) throw InputError("--subject " + text, "expected auto or x,y,z,r (four numbers)");
    if (!(v[3] > 0)) throw InputError("--subject " + text, "the radius must be positive");
    return {{v[0], v[1], v[2]}, v[3]};
}

std::vector<uint8_t> subject_mask(const RenderOutput& unpruned, const Camera& camera, const SubjectBall& ball) {
    const size_t pixels = size_t(unpruned.width) * size_t(unpruned.height);
    if (unpruned.width != camera.width || unpruned.height != camera.height || unpruned.alpha.size() != pixels ||
        unpruned.depth.size() != pixels)
        throw InputError("subject mask of camera '" + camera.name + "'", "the render is not the camera's size");
    // The ball in camera space: a pixel's point is centre + depth * ((x + 0.5 - cx) / fx, (y + 0.5 - cy) / fy, 1).
    const glm::dvec3 centre = camera.to_camera(ball.centre);
    const double r2 = ball.radius * ball.radius;
    std::vector<uint8_t> mask(pixels, 0);
    for (int y = 0; y < unpruned.height; ++y)
        for (int x = 0; x < unpruned.width; ++x) {
            const size_t p = size_t(y) * unpruned.width + x;
            if (!(unpruned.alpha[p] > kSubjectMinAlpha)) continue;
            const double z = unpruned.depth[p];
            const glm::dvec3 point((x + 0.5 - camera.cx) / camera.fx * z, (y + 0.5 - camera.cy) / camera.fy * z, z);
            const glm::dvec3 d = point - centre;
            mask[p] = glm::dot(d, d) <= r2;
        }
    return mask;
}

}  // namespace vksplat::eval
