// NeRF transforms files: OpenGL camera axes become OpenCV ones, sizes come from w/h or the images.
#include <gtest/gtest.h>

#include <cmath>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::io::test {
namespace {

void write_blank_png(const std::filesystem::path& path, int width, int height) {
    std::filesystem::create_directories(path.parent_path());
    const std::vector<float> rgb(static_cast<size_t>(width) * height * 3, 0.5f);
    write_png_rgb(path, width, height, rgb.data(), 8);
}

// Frame 0 sits at z = 5 with the identity rotation: in OpenGL axes it looks along -z, at the
// origin. Frame 1 sits at x = 5, turned to look along -x, also at the origin.
const char* kTransforms = R"({
  "camera_angle_x": 0.8,
  "frames": [
    {"file_path": "./train/r_0", "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]},
    {"file_path": "./train/r_1.png", "transform_matrix": [[0, 0, 1, 5], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]]}
  ]
})";

TEST(NerfTransforms, FlipsOpenGlAxesAndReadsImageSizes) {
    ScratchDir dir;
    write_bytes(dir / "transforms_train.json", kTransforms);
    write_blank_png(dir / "train" / "r_0.png", 40, 30);
    write_blank_png(dir / "train" / "r_1.png", 20, 10);
    const auto cameras = read_nerf_transforms(dir / "transforms_train.json");
    ASSERT_EQ(cameras.size(), 2u);

    const Camera& front = cameras[0];
    EXPECT_EQ(front.name, "./train/r_0");
    EXPECT_EQ(front.width, 40);
    EXPECT_EQ(front.height, 30);
    EXPECT_DOUBLE_EQ(front.fx, 0.5 * 40 / std::tan(0.4));
    EXPECT_DOUBLE_EQ(front.fy, front.fx);
    EXPECT_EQ(front.cx, 20);
    EXPECT_EQ(front.cy, 15);
    // A point along OpenGL -z from the camera is in front: positive OpenCV z.
    EXPECT_NEAR(front.to_camera({0, 0, 0}).z, 5, 1e-12);
    // World up is OpenGL camera +y, so OpenCV camera -y (y points down the image).
    EXPECT_NEAR(front.to_camera({0, 1, 0}).y, -1, 1e-12);
    // Camera x is not flipped.
    EXPECT_NEAR(front.to_camera({1, 0, 0}).x, 1, 1e-12);

    const Camera& side = cameras[1];
    EXPECT_EQ(side.width, 20);
    EXPECT_EQ(side.height, 10);
    EXPECT_NEAR(side.to_camera({0, 0, 0}).z, 5, 1e-12);
    EXPECT_NEAR(side.to_camera({0, 0, 0}).x, 0, 1e-12);
    EXPECT_NEAR(side.centre().x, 5, 1e-12);
    // The dispatcher recognises the format.
    EXPECT_EQ(read_cameras(dir / "transforms_train.json").size(), 2u);
}

TEST(NerfTransforms, SizeAndFieldOfViewKeys) {
    ScratchDir dir;
    write_bytes(dir / "t.json", R"({"camera_angle_x": 1.0, "camera_angle_y": 0.5, "w": 100, "h": 50, "cx": 49,
      "frames": [{"file_path": "missing", "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
                 {"file_path": "own", "w": 10, "h": 8,
                  "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
    const auto cameras = read_nerf_transforms(dir / "t.json");
    ASSERT_EQ(cameras.size(), 2u);
    EXPECT_EQ(cameras[0].width, 100);
    EXPECT_EQ(cameras[0].height, 50);
    EXPECT_DOUBLE_EQ(cameras[0].fx, 50 / std::tan(0.5));
    EXPECT_DOUBLE_EQ(cameras[0].fy, 25 / std::tan(0.25));
    EXPECT_EQ(cameras[0].cx, 49);
    EXPECT_EQ(cameras[0].cy, 25);
    EXPECT_EQ(cameras[1].width, 10);
    EXPECT_EQ(cameras[1].height, 8);
}

TEST(NerfTransforms, Errors) {
    ScratchDir dir;
    const auto path = dir / "t.json";
    write_bytes(path, R"({"frames": []})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "missing key 'camera_angle_x'"});

    write_bytes(path, R"({"camera_angle_x": 0.5, "frames": [{"file_path": "a", "w": 4, "h": 4}]})");
    expect_input_error([&] { read_nerf_transforms(path); },
                       {"t.json", "frame 0 ('a')", "missing key 'transform_matrix'"});

    write_bytes(path, R"({"camera_angle_x": 0.5, "frames": [{"file_path": "gone",
      "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "frame 0 ('gone')", "gone.png"});

    write_bytes(path, R"({"camera_angle_x": 0.5, "frames": [{"file_path": "a", "w": 4, "h": 4,
      "transform_matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "frame 0 ('a')", "4 rows of 4 numbers"});

    write_bytes(path, R"({"camera_angle_x": 0, "frames": [{"file_path": "a", "w": 4, "h": 4,
      "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "frame 0 ('a')", "focal length"});

    write_bytes(path, R"({"camera_angle_x": 1e-300, "frames": [{"file_path": "a", "w": 4, "h": 4,
      "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "frame 0 ('a')", "makes no picture"});

    write_bytes(path, R"({"camera_angle_x": -1e400, "frames": []})");
    expect_input_error([&] { read_nerf_transforms(path); }, {"t.json", "number overflow"});

    write_bytes(path, R"({"camera_angle_x": 0.5})");
    expect_input_error([&] { read_cameras(path); }, {"t.json", "neither an INRIA cameras.json"});
}

}  // namespace
}  // namespace vksplat::io::test
