// CameraControls: orbit keeps the focus point, fly keeps the eye, a dataset camera is shown
// exactly, framing puts a scene in the middle of the picture.
#include <gtest/gtest.h>

#include "support/scenes.hpp"
#include "vksplat/camera/camera_controls.hpp"
#include "vksplat/scene/demo_scene.hpp"
#include "vksplat/error.hpp"

namespace vksplat::test {
namespace {

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-9) {
    EXPECT_NEAR(glm::length(a - b), 0.0, tolerance) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x
                                                    << ", " << b.y << ", " << b.z << ")";
}

// Where a world point lands in the picture.
glm::dvec2 project(const Camera& camera, const glm::dvec3& world) {
    const glm::dvec3 p = camera.to_camera(world);
    return {camera.fx * p.x / p.z + camera.cx, camera.fy * p.y / p.z + camera.cy};
}

TEST(CameraControls, StartsLookingAtTheTarget) {
    const CameraControls controls({0, -5, 1}, {0, 0, 1}, {0, 0, 1});
    expect_near(controls.target(), {0, 0, 1});
    const Camera view = controls.camera(64, 48);
    const glm::dvec2 centre = project(view, {0, 0, 1});
    EXPECT_NEAR(centre.x, 32, 1e-9);
    EXPECT_NEAR(centre.y, 24, 1e-9);
    // Up in the world is up in the picture: a point above the target lands above the centre.
    EXPECT_LT(project(view, {0, 0, 2}).y, 24);
}

TEST(CameraControls, OrbitKeepsTheFocusPointAndFlyKeepsTheEye) {
    CameraControls orbit({3, 0, 0}, {0, 0, 0}, {0, 0, 1});
    orbit.rotate(120, -40);
    expect_near(orbit.target(), {0, 0, 0});
    EXPECT_NEAR(orbit.distance(), 3, 1e-12);
    EXPECT_GT(glm::length(orbit.eye() - glm::dvec3(3, 0, 0)), 0.5);

    CameraControls fly({3, 0, 0}, {0, 0, 0}, {0, 0, 1});
    fly.set_mode(CameraControls::Mode::fly);
    fly.rotate(120, -40);
    expect_near(fly.eye(), {3, 0, 0});
    fly.move({0, 0, 1}, 0.5);  // forward for half a second at one focus distance a second
    EXPECT_NEAR(glm::length(fly.eye() - glm::dvec3(3, 0, 0)), 1.5, 1e-12);
}

TEST(CameraControls, DraggingRightTurnsTheFlyViewRight) {
    CameraControls fly({0, 0, 0}, {0, 1, 0}, {0, 0, 1});
    fly.set_mode(CameraControls::Mode::fly);
    fly.rotate(50, 0);
    EXPECT_GT(fly.forward().x, 0.1);  // looking along +y with z up, right is +x
}

TEST(CameraControls, PitchStopsShortOfTheUpAxis) {
    CameraControls controls({3, 0, 0}, {0, 0, 0}, {0, 0, 1});
    controls.rotate(0, -100000);
    EXPECT_LT(std::abs(controls.forward().z), 1.0);
    EXPECT_NO_THROW(controls.camera(32, 32).validate());
}

TEST(CameraControls, ZoomAndPanMoveAsDocumented) {
    CameraControls controls({0, -4, 0}, {0, 0, 0}, {0, 0, 1});
    controls.zoom(1);
    EXPECT_NEAR(controls.distance(), 3.6, 1e-12);
    expect_near(controls.target(), {0, 0, 0});
    controls.pan(0, 100, 100);  // a drag of the picture's height down moves the eye up by the distance
    expect_near(controls.eye(), {0, -3.6, 3.6});
}

TEST(CameraControls, ADatasetCameraIsShownExactly) {
    const Camera dataset = Camera::look_at({1, 2, 3}, {0, 0, 0}, {0.3, 0, 1}, 80, 60, 70, 70);
    CameraControls controls({0, -5, 0}, {0, 0, 0}, {0, 0, 1});
    controls.jump_to(dataset, 2.0);
    const Camera view = controls.camera(160, 120);  // same aspect, twice the size
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(view.rotation[c][r], dataset.rotation[c][r], 1e-12);
    expect_near(view.translation, dataset.translation);
    EXPECT_NEAR(view.fy, 140, 1e-9);
    EXPECT_NEAR(view.fx, 140, 1e-9);
    expect_near(controls.target(), dataset.centre() + glm::normalize(-dataset.centre()) * 2.0, 1e-9);
    controls.rotate(1, 0);  // any motion leaves it, keeping the field of view
    EXPECT_NEAR(controls.camera(160, 120).fy, 140, 1e-9);
}

TEST(CameraControls, UpComesFromTheDatasetCameras) {
    const auto cameras = make_orbit_cameras(8, 32, 24, 4.0, 30.0);  // +z up
    expect_near(CameraControls::up_of(cameras, {1, 0, 0}), {0, 0, 1}, 1e-9);
    expect_near(CameraControls::up_of({}, {1, 0, 0}), {1, 0, 0});
}

TEST(CameraControls, FramingPutsTheSceneInTheMiddle) {
    const GaussianCloud scene = make_demo_scene();
    const CameraControls controls = CameraControls::framing(scene.positions, {0, 0, 1});
    const Camera view = controls.camera(100, 100);
    const glm::dvec2 at = project(view, controls.target());
    EXPECT_NEAR(at.x, 50, 1e-6);
    EXPECT_NEAR(at.y, 50, 1e-6);
    // The knot (radius 0.9 about the origin) is wholly inside the picture.
    for (const glm::dvec3 p : {glm::dvec3(0.9, 0, 0), glm::dvec3(-0.9, 0, 0), glm::dvec3(0, 0.9, 0), glm::dvec3(0, -0.9, 0)}) {
        const glm::dvec2 q = project(view, p);
        EXPECT_GT(q.x, 0);
        EXPECT_LT(q.x, 100);
        EXPECT_GT(q.y, 0);
        EXPECT_LT(q.y, 100);
    }
}

TEST(CameraControls, DegenerateStartsAreRefused) {
    EXPECT_THROW(CameraControls({1, 1, 1}, {1, 1, 1}, {0, 0, 1}), InputError);
    EXPECT_THROW(CameraControls({0, 0, 0}, {1, 1, 1}, {0, 0, 0}), InputError);
}

}  // namespace
}  // namespace vksplat::test
