// Building cameras: from a viewpoint and a target, and for another image size.
#include <cmath>

#include "vksplat/camera/camera.hpp"
#include "vksplat/error.hpp"

namespace vksplat {

Camera Camera::look_at(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, int width,
                       int height, double fx, double fy) {
    const glm::dvec3 view = target - eye;
    if (!(glm::length(view) > 0.0)) throw InputError("Camera::look_at", "the eye and the target coincide");
    const glm::dvec3 forward = glm::normalize(view);
    const glm::dvec3 side = glm::cross(forward, up);
    if (!(glm::length(side) > 0.0))
        throw InputError("Camera::look_at", "the up vector is parallel to the viewing direction (or zero)");
    // OpenCV axes: x to the right of the picture, y down (forward x right), z forward.
    const glm::dvec3 x = glm::normalize(side);
    const glm::dvec3 y = glm::cross(forward, x);

    Camera camera;
    camera.width = width;
    camera.height = height;
    camera.fx = fx;
    camera.fy = fy;
    camera.cx = width / 2.0;
    camera.cy = height / 2.0;
    // The camera axes are the rows of the world-to-camera rotation (glm indexes [column][row]).
    for (int c = 0; c < 3; ++c) {
        camera.rotation[c][0] = x[c];
        camera.rotation[c][1] = y[c];
        camera.rotation[c][2] = forward[c];
    }
    camera.translation = -(camera.rotation * eye);
    return camera;
}

Camera Camera::resized(int new_width, int new_height) const {
    Camera out = *this;
    const double sx = static_cast<double>(new_width) / width;
    const double sy = static_cast<double>(new_height) / height;
    out.width = new_width;
    out.height = new_height;
    out.fx = fx * sx;
    out.fy = fy * sy;
    out.cx = cx * sx;
    out.cy = cy * sy;
    return out;
}

}  // namespace vksplat
