#include "vksplat/camera/camera_controls.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "vksplat/error.hpp"
#include "stats/median.hpp"

namespace vksplat {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxPitch = (90.0 - 1.0) * kPi / 180.0;
constexpr double kRadiansPerPixel = 0.005;
constexpr double kZoomStep = 0.1;

}  // namespace

CameraControls::CameraControls(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up) : eye_(eye) {
    if (glm::length(up) == 0.0) throw InputError("camera controls", "the up direction is zero");
    const glm::dvec3 view = target - eye;
    distance_ = glm::length(view);
    if (!(distance_ > 0.0)) throw InputError("camera controls", "eye and target coincide");
    up_ = glm::normalize(up);
    // Any direction across up will do for yaw 0; the axis least parallel to up is the stablest.
    const glm::dvec3 a = std::abs(up_.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    across_ = glm::normalize(a - up_ * glm::dot(a, up_));
    across2_ = glm::cross(up_, across_);
    const glm::dvec3 f = view / distance_;
    pitch_ = std::clamp(std::asin(std::clamp(glm::dot(f, up_), -1.0, 1.0)), -kMaxPitch, kMaxPitch);
    yaw_ = std::atan2(glm::dot(f, across2_), glm::dot(f, across_));
}

CameraControls CameraControls::framing(std::span<const float> positions, const glm::dvec3& up) {
    glm::dvec3 centre(0.0);
    double radius = 1.0;
    const size_t count = positions.size() / 3;
    if (count > 0) {
        std::vector<double> axis(count);
        for (int a = 0; a < 3; ++a) {
            for (size_t i = 0; i < count; ++i) axis[i] = positions[3 * i + a];
            centre[a] = stats::median(axis);
        }
        std::vector<double> spread(count);
        for (size_t i = 0; i < count; ++i)
            spread[i] = glm::length(glm::dvec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]) - centre);
        // The 90th percentile ignores far floaters; 0 for a single point still needs a distance.
        std::nth_element(spread.begin(), spread.begin() + long(spread.size() * 9 / 10), spread.end());
        radius = std::max(spread[spread.size() * 9 / 10], 1e-3);
    }
    CameraControls controls(centre + glm::dvec3(1, 0, 0), centre, up);
    controls.pitch_ = -25.0 * kPi / 180.0;  // looking down at it
    controls.yaw_ = 0.0;
    // Far enough that a sphere of `radius` fits the 50 degree field of view.
    controls.distance_ = radius / std::sin(controls.fov_y_ / 2);
    controls.eye_ = centre - controls.forward() * controls.distance_;
    return controls;
}

glm::dvec3 CameraControls::up_of(const std::vector<Camera>& cameras, const glm::dvec3& fallback) {
    glm::dvec3 sum(0.0);
    // Picture-up is -y of the camera (OpenCV axes), in world coordinates -R^T e_y: minus row 1 of R.
    for (const auto& c : cameras) sum -= glm::dvec3(c.rotation[0][1], c.rotation[1][1], c.rotation[2][1]);
    return glm::length(sum) > 1e-6 * double(cameras.size()) ? glm::normalize(sum) : fallback;
}

glm::dvec3 CameraControls::forward() const {
    return std::cos(pitch_) * (std::cos(yaw_) * across_ + std::sin(yaw_) * across2_) + std::sin(pitch_) * up_;
}

void CameraControls::jump_to(const Camera& camera, double focus_distance) {
    const CameraControls pose(camera.centre(),
                              camera.centre() + glm::dvec3(camera.rotation[0][2], camera.rotation[1][2],
                                                           camera.rotation[2][2]) * focus_distance,
                              up_);
    eye_ = pose.eye_;
    yaw_ = pose.yaw_;
    pitch_ = pose.pitch_;
    distance_ = focus_distance;
    fov_y_ = 2.0 * std::atan(camera.height / (2.0 * camera.fy));
    dataset_view_ = camera;
}

void CameraControls::rotate(double dx, double dy) {
    leave_dataset_view();
    const glm::dvec3 focus = target();
    // Dragging right turns the view right: yaw grows toward across2 = up x across.
    yaw_ -= dx * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ - dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    if (mode_ == Mode::orbit) eye_ = focus - forward() * distance_;
}

void CameraControls::pan(double dx, double dy, int picture_height) {
    leave_dataset_view();
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, up_));
    const glm::dvec3 picture_up = glm::cross(right, f);
    const double scale = distance_ / std::max(picture_height, 1);
    // The scene follows the mouse: the eye moves the other way.
    eye_ += (-dx * right + dy * picture_up) * scale;
}

void CameraControls::zoom(double steps) {
    leave_dataset_view();
    if (mode_ == Mode::orbit) {
        const glm::dvec3 focus = target();
        distance_ *= std::pow(1.0 - kZoomStep, steps);
        eye_ = focus - forward() * distance_;
    } else {
        eye_ += forward() * distance_ * kZoomStep * steps;
    }
}

void CameraControls::move(const glm::dvec3& right_up_forward, double seconds) {
    leave_dataset_view();
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, up_));
    eye_ += (right_up_forward.x * right + right_up_forward.y * up_ + right_up_forward.z * f) * distance_ * seconds;
}

Camera CameraControls::camera(int width, int height) const {
    const double fy = height / (2.0 * std::tan(fov_y_ / 2));
    if (dataset_view_) {
        Camera view = *dataset_view_;
        view.fx = dataset_view_->fx / dataset_view_->fy * fy;
        view.fy = fy;
        view.width = width;
        view.height = height;
        view.cx = width / 2.0;
        view.cy = height / 2.0;
        return view;
    }
    // Pitch never reaches +-90 degrees, so up is never parallel to the view.
    return Camera::look_at(eye_, target(), up_, width, height, fy, fy);
}

}  // namespace vksplat
