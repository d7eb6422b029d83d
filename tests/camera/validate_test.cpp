// Camera::validate: every defect is reported as an InputError naming the camera and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "vksplat/camera/camera.hpp"
#include "vksplat/error.hpp"

namespace vksplat {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Camera good_camera() {
    Camera camera = Camera::look_at({1.0, 2.0, 3.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 640, 480, 500.0, 510.0);
    camera.name = "r_7.png";
    return camera;
}

// Applies `defect` to a good camera and checks the error names it and mentions `problem`.
void expect_rejected(const std::function<void(Camera&)>& defect, const std::string& problem) {
    Camera camera = good_camera();
    defect(camera);
    try {
        camera.validate();
        ADD_FAILURE() << "accepted a camera with: " << problem;
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("camera 'r_7.png': ", 0), 0u) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
}

TEST(Validate, AcceptsAGoodCamera) {
    EXPECT_NO_THROW(good_camera().validate());
    Camera off_centre = good_camera();
    off_centre.cx = -20.0;  // a principal point outside the image is unusual but well defined
    EXPECT_NO_THROW(off_centre.validate());
}

TEST(Validate, RejectsNonPositiveSizes) {
    expect_rejected([](Camera& c) { c.width = 0; }, "image size 0x480");
    expect_rejected([](Camera& c) { c.height = -1; }, "image size 640x-1");
}

TEST(Validate, RejectsBadFocalLengths) {
    expect_rejected([](Camera& c) { c.fx = 0.0; }, "focal length");
    expect_rejected([](Camera& c) { c.fy = -3.0; }, "focal length");
    expect_rejected([](Camera& c) { c.fx = kNaN; }, "focal length");
    expect_rejected([](Camera& c) { c.fy = kInf; }, "focal length");
}

// Finite and positive, yet no picture: 1e300 is infinite once the GPU takes it as a float.
TEST(Validate, RejectsFocalLengthsThatMakeNoPicture) {
    expect_rejected([](Camera& c) { c.fx = 1e300; }, "focal length (1e+300, 510) makes no picture of a 640x480 image");
    expect_rejected([](Camera& c) { c.fy = 480 * 1.01e7; }, "fx / width and fy / height must lie in [1e-3, 1e7]");
    expect_rejected([](Camera& c) { c.fx = 640 * 0.99e-3; }, "makes no picture");
    Camera widest = good_camera(), narrowest = good_camera();
    widest.fx = 640 * 1e-3;
    narrowest.fy = 480 * 1e7;
    EXPECT_NO_THROW(widest.validate());
    EXPECT_NO_THROW(narrowest.validate());
}

TEST(Validate, RejectsNonFiniteValues) {
    expect_rejected([](Camera& c) { c.cx = kInf; }, "principal point");
    expect_rejected([](Camera& c) { c.cy = kNaN; }, "principal point");
    expect_rejected([](Camera& c) { c.translation.y = kNaN; }, "translation is not finite");
    expect_rejected([](Camera& c) { c.rotation[2][1] = kInf; }, "rotation is not finite");
}

TEST(Validate, RejectsRotationsThatAreNotRotations) {
    expect_rejected([](Camera& c) { c.rotation *= 1.001; }, "not orthonormal");
    expect_rejected([](Camera& c) { c.rotation[0][0] += 1e-3; }, "not orthonormal");
    expect_rejected([](Camera& c) { c.rotation[1] = -c.rotation[1]; }, "reflection");
    // Rounding far below the tolerance is accepted.
    Camera rounded = good_camera();
    rounded.rotation[0][0] += 1e-6;
    EXPECT_NO_THROW(rounded.validate());
}

}  // namespace
}  // namespace vksplat
