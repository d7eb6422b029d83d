#pragma once
// CameraControls: interactive camera motion for a viewer, free of any windowing library. The view
// is an eye, a heading (yaw and pitch about the world's up direction) and a focus distance; orbit
// turns the eye about the focus point, fly turns the view about the eye.
#include <glm/glm.hpp>

#include <optional>
#include <span>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat {

class CameraControls {
public:
    enum class Mode { orbit, fly };

    // Looking from `eye` at `target`; `up` is the world's up direction (need not be unit length).
    // Throws InputError if eye and target coincide or up is zero.
    CameraControls(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);
    // Looks at the bulk of a scene, given as its points' positions (x, y, z per point, as
    // GaussianCloud::positions holds them), at their median from far enough to see most of
    // them, from 25 degrees above its horizon.
    static CameraControls framing(std::span<const float> positions, const glm::dvec3& up);
    // The world's up as a set of dataset cameras agree on it (the mean of their picture-up
    // directions); `fallback` when there are none or they cancel out.
    static glm::dvec3 up_of(const std::vector<Camera>& cameras, const glm::dvec3& fallback);

    // Shows exactly this dataset camera (its roll and field of view too) until the next motion;
    // the focus point is `focus_distance` in front of it.
    void jump_to(const Camera& camera, double focus_distance);

    Mode mode() const { return mode_; }
    void set_mode(Mode mode) { mode_ = mode; }

    // A drag of (dx, dy) pixels: orbit turns the eye about the focus point, fly turns the view.
    // Pitch stops 1 degree short of straight up or down.
    void rotate(double dx, double dy);
    // Slides eye and focus point across the view; a drag of the picture's height moves them by
    // the focus distance.
    void pan(double dx, double dy, int picture_height);
    // Scroll steps: orbit moves the eye toward (positive) or away from the focus point by 10% a
    // step; fly moves eye and focus point forward by 10% of the focus distance a step.
    void zoom(double steps);
    // Fly keys: moves eye and focus point by (right, up, forward) * speed * seconds, where speed is
    // the focus distance per second.
    void move(const glm::dvec3& right_up_forward, double seconds);

    // The view for a picture of width x height. Until jump_to's camera is left, its pose and
    // vertical field of view (the focal lengths scale with the height, principal point centred).
    Camera camera(int width, int height) const;

    glm::dvec3 eye() const { return eye_; }
    glm::dvec3 target() const { return eye_ + forward() * distance_; }
    double distance() const { return distance_; }
    glm::dvec3 forward() const;

private:
    void leave_dataset_view() { dataset_view_.reset(); }

    Mode mode_ = Mode::orbit;
    glm::dvec3 up_, across_, across2_;  // an orthonormal basis with up_ first
    glm::dvec3 eye_;
    double yaw_ = 0, pitch_ = 0, distance_ = 1;
    double fov_y_ = 0.8726646259971648;  // 50 degrees
    std::optional<Camera> dataset_view_;
};

}  // namespace vksplat
