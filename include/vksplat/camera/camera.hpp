#pragma once
// Camera: a pinhole camera with OpenCV axes (x right, y down, z forward).
#include <glm/glm.hpp>
#include <string>

namespace vksplat {

struct Camera {
    std::string name;       // image name as the camera file gives it (may include an extension)
    // "train" or "test" where the camera file says which (an INRIA cameras.json's "split", as
    // bonsai's and vksplat train's output have); empty otherwise. jobs::default_test_views reads it.
    std::string split;
    int width = 0;
    int height = 0;
    double fx = 0, fy = 0;  // focal lengths in pixels
    // Principal point in continuous pixel coordinates: pixel (i, j) covers [i, i+1) x [j, j+1),
    // so a centred camera has cx = width / 2, cy = height / 2 (the reference rasterizer's case).
    double cx = 0, cy = 0;
    // World-to-camera rigid transform: p_cam = rotation * p_world + translation.
    // glm is column-major: rotation[c][r] is row r, column c.
    glm::dmat3 rotation{1.0};
    glm::dvec3 translation{0.0};

    glm::dvec3 to_camera(const glm::dvec3& world) const { return rotation * world + translation; }
    // Camera centre in world coordinates (-R^T t).
    glm::dvec3 centre() const { return -(glm::transpose(rotation) * translation); }
    // tan of half the field of view, as the reference rasterizer defines it (from the image size).
    double tan_half_fov_x() const { return width / (2.0 * fx); }
    double tan_half_fov_y() const { return height / (2.0 * fy); }

    // A camera at `eye` looking at `target` with `up` pointing up in the picture (OpenCV axes:
    // x = normalise(forward x up), y = forward x x). Principal point at the centre.
    // Throws InputError when eye and target coincide or up is parallel to the view direction.
    static Camera look_at(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up,
                          int width, int height, double fx, double fy);

    // The same camera for another image size: focal lengths and principal point scale with it.
    Camera resized(int new_width, int new_height) const;

    // Throws InputError naming the camera and the problem: non-positive size,
    // zero/negative/non-finite focal length, non-finite or non-orthonormal rotation.
    void validate() const;
    // What validate() would complain about, without the camera's name; empty when valid.
    std::string problem() const;
};

}  // namespace vksplat
