// INRIA cameras.json: poses, intrinsics, and errors that name the file and the camera.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io::test {
namespace {

// A camera at (0, 0, -4) looking along +z (rotation = identity), and one at (4, 0, 0) looking along
// -x, whose x axis is world +z; rotations are camera-to-world, written as rows.
const char* kTwoCameras = R"([
  {"id": 0, "img_name": "front", "width": 640, "height": 480, "position": [0, 0, -4],
   "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 500, "fy": 510},
  {"id": 1, "img_name": "side.png", "width": 100, "height": 50, "position": [4, 0, 0],
   "rotation": [[0, 0, -1], [0, 1, 0], [1, 0, 0]], "fx": 80, "fy": 80, "cx": 40.5, "cy": 20}
])";

TEST(InriaCameras, ReadsPosesAndIntrinsics) {
    ScratchDir dir;
    write_bytes(dir / "cameras.json", kTwoCameras);
    const auto cameras = read_inria_cameras(dir / "cameras.json");
    ASSERT_EQ(cameras.size(), 2u);

    const Camera& front = cameras[0];
    EXPECT_EQ(front.name, "front");
    EXPECT_EQ(front.width, 640);
    EXPECT_EQ(front.height, 480);
    EXPECT_EQ(front.fx, 500);
    EXPECT_EQ(front.fy, 510);
    EXPECT_EQ(front.cx, 320);  // the image centre by default
    EXPECT_EQ(front.cy, 240);
    const glm::dvec3 origin_in_front = front.to_camera({0, 0, 0});
    EXPECT_DOUBLE_EQ(origin_in_front.z, 4.0);

    const Camera& side = cameras[1];
    EXPECT_EQ(side.name, "side.png");
    EXPECT_EQ(side.cx, 40.5);
    EXPECT_EQ(side.cy, 20);
    // Its z axis (third column of camera-to-world) is world -x: the origin lies 4 ahead.
    const glm::dvec3 origin_in_side = side.to_camera({0, 0, 0});
    EXPECT_NEAR(origin_in_side.x, 0, 1e-12);
    EXPECT_NEAR(origin_in_side.z, 4, 1e-12);
    // Its x axis (first column) is world +z.
    EXPECT_NEAR(side.to_camera({0, 0, 1}).x, 1, 1e-12);
    const glm::dvec3 centre = side.centre();
    EXPECT_NEAR(centre.x, 4, 1e-12);
}

TEST(InriaCameras, LegoCameraZeroProjectsAsComputedByHand) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto cameras = read_inria_cameras(vksplat::test::shared_data_dir() / "lego" / "cameras.json");
    ASSERT_EQ(cameras.size(), 100u);
    const Camera& camera = cameras[0];
    EXPECT_EQ(camera.name, "r_0");

    // cameras.json[0], copied from the file.
    const double position[3] = {-0.05379832163453101, 3.8454704284667964, 1.2080823183059688};
    const double rotation[3][3] = {{-0.9999021887779235, -0.004192245192825794, 0.013345719315111635},
                                   {-0.013988681137561795, 0.2996590733528137, -0.95394366979599},
                                   {-4.6566128701121584e-10, -0.9540371894836427, -0.299688309431076}};
    const double fx = 1111.1110311937682;
    const double point[3] = {0.3, -0.2, 0.5};
    // p_cam = rotation^T (p - position); pixel = f * (x, y) / z + image centre.
    double p_cam[3] = {0, 0, 0};
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) p_cam[c] += rotation[r][c] * (point[r] - position[r]);
    const double u = fx * p_cam[0] / p_cam[2] + 400;
    const double v = fx * p_cam[1] / p_cam[2] + 400;

    const glm::dvec3 q = camera.to_camera({point[0], point[1], point[2]});
    EXPECT_NEAR(camera.fx * q.x / q.z + camera.cx, u, 1e-9);
    EXPECT_NEAR(camera.fy * q.y / q.z + camera.cy, v, 1e-9);
    EXPECT_NEAR(q.z, p_cam[2], 1e-12);
    // The Blender cameras look at the origin: it lands near the image centre.
    const glm::dvec3 o = camera.to_camera({0, 0, 0});
    EXPECT_NEAR(camera.fx * o.x / o.z + camera.cx, 400, 2.0);
    EXPECT_NEAR(camera.fy * o.y / o.z + camera.cy, 400, 2.0);
}

TEST(InriaCameras, ErrorsNameTheFileAndTheCamera) {
    ScratchDir dir;
    const auto path = dir / "cams.json";
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "no such file"});

    write_bytes(path, "[{\"img_name\": \"a\", ");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "malformed JSON"});

    const std::string good = R"({"img_name": "a", "width": 8, "height": 8, "position": [0, 0, 0],
                                 "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 5, "fy": 5})";
    write_bytes(path, "[" + good + R"(, {"img_name": "b", "width": 8, "height": 8, "position": [0, 0, 0],
                       "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 1 ('b')", "missing key 'fx'"});

    write_bytes(path, "[" + good + R"(, {"img_name": "c", "width": "8", "height": 8, "position": [0, 0, 0],
                       "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 5, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 1 ('c')", "'width' is a string"});

    write_bytes(path, R"([{"img_name": "d", "width": 8, "height": 8, "position": [0, 0],
                          "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 5, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); },
                       {"cams.json", "camera 0 ('d')", "'position' is not a list of 3"});

    write_bytes(path, R"([{"img_name": "e", "width": 8, "height": 8, "position": [0, 0, 0],
                          "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 0, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 0 ('e')", "focal length"});

    // Beyond a double: nlohmann's out_of_range, which once escaped without the file's name.
    write_bytes(path, R"([{"img_name": "e", "width": 8, "height": 8, "position": [0, 0, 0],
                          "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 1e400, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "number overflow parsing '1e400'"});
    expect_input_error([&] { read_cameras(path); }, {"cams.json", "number overflow parsing '1e400'"});

    // Finite, but the picture would be blank.
    write_bytes(path, R"([{"img_name": "e", "width": 8, "height": 8, "position": [0, 0, 0],
                          "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 1e300, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 0 ('e')", "makes no picture"});

    write_bytes(path, R"([{"img_name": "f", "width": 8, "height": 8, "position": [0, 0, 0],
                          "rotation": [[2, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 5, "fy": 5}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 0 ('f')", "orthonormal"});

    write_bytes(path, R"({"cameras": []})");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "expected a list of cameras"});

    write_bytes(path, R"([{"width": 8}])");
    expect_input_error([&] { read_inria_cameras(path); }, {"cams.json", "camera 0", "missing key 'img_name'"});
}

}  // namespace
}  // namespace vksplat::io::test
