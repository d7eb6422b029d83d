// COLMAP models: text and binary files decode alike (as cameras and as a data folder that
// undistorts), the snowmiku model matches its cameras.json, and malformed models are reported with
// the file at fault.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "io/io_test_helpers.hpp"
#include "support/test_data.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/dataset.hpp"

namespace vksplat::io::test {
namespace {

struct TestCamera {
    uint32_t id;
    int model_id;
    const char* model;
    uint64_t width, height;
    std::vector<double> params;
};

struct TestImage {
    uint32_t id;
    double q[4];
    double t[3];
    uint32_t camera_id;
    std::string name;
    std::vector<std::array<double, 2>> points;
};

const std::vector<TestCamera> kCameras = {
    {1, 1, "PINHOLE", 64, 48, {50, 52, 32, 24}},
    {2, 2, "SIMPLE_RADIAL", 30, 20, {25, 15, 10, 0.01}},
    {3, 4, "OPENCV", 40, 30, {35, 36, 20, 15, 0.1, -0.05, 0.001, 0.002}},
    {4, 0, "SIMPLE_PINHOLE", 16, 12, {14, 8.5, 6}},
    {5, 3, "RADIAL", 32, 24, {30, 16, 12, -0.05, 0.01}},
    {6, 6, "FULL_OPENCV", 48, 36, {40, 41, 24, 18, -0.1, 0.02, 0.001, -0.001, 0.003, 0.01, 0.002, 0.001}},
};

// Unsorted names; the first is a 90 degree turn about z, the others arbitrary (unnormalised).
const std::vector<TestImage> kImages = {
    {7, {1, 0, 0, 0}, {0, 0, 1}, 4, "d.png", {}},
    {5, {std::sqrt(0.5), 0, 0, std::sqrt(0.5)}, {1, 2, 3}, 1, "c.png", {{1.5, 2.5}, {3, 4}}},
    {2, {0.9, 0.1, -0.3, 0.2}, {-1, 0.5, 4}, 2, "a.png", {}},
    {9, {2.0, -0.4, 0.6, 1.0}, {0.25, -2, 7}, 3, "b.png", {{0, 0}}},
    {3, {1, 0, 0, 0}, {0, 1, 0}, 5, "e.png", {}},
    {4, {1, 0, 0, 0}, {1, 1, 0}, 6, "f.png", {}},
};

void write_text_model(const std::filesystem::path& folder) {
    std::filesystem::create_directories(folder);
    std::ostringstream cameras;
    cameras.precision(17);
    cameras << "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
    for (const auto& camera : kCameras) {
        cameras << camera.id << ' ' << camera.model << ' ' << camera.width << ' ' << camera.height;
        for (double p : camera.params) cameras << ' ' << p;
        cameras << '\n';
    }
    write_bytes(folder / "cameras.txt", cameras.str());
    std::ostringstream images;
    images.precision(17);
    images << "# Image list with two lines of data per image:\n";
    for (const auto& image : kImages) {
        images << image.id;
        for (double q : image.q) images << ' ' << q;
        for (double t : image.t) images << ' ' << t;
        images << ' ' << image.camera_id << ' ' << image.name << '\n';
        for (const auto& point : image.points) images << point[0] << ' ' << point[1] << " -1 ";
        images << '\n';
    }
    write_bytes(folder / "images.txt", images.str());
}

// As COLMAP's WriteCamerasBinary and WriteImagesBinary lay the files out.
void write_binary_model(const std::filesystem::path& folder) {
    std::filesystem::create_directories(folder);
    std::string cameras;
    append<uint64_t>(cameras, kCameras.size());
    for (const auto& camera : kCameras) {
        append<uint32_t>(cameras, camera.id);
        append<int32_t>(cameras, camera.model_id);
        append<uint64_t>(cameras, camera.width);
        append<uint64_t>(cameras, camera.height);
        for (double p : camera.params) append<double>(cameras, p);
    }
    write_bytes(folder / "cameras.bin", cameras);
    std::string images;
    append<uint64_t>(images, kImages.size());
    for (const auto& image : kImages) {
        append<uint32_t>(images, image.id);
        for (double q : image.q) append<double>(images, q);
        for (double t : image.t) append<double>(images, t);
        append<uint32_t>(images, image.camera_id);
        images += image.name;
        images += '\0';
        append<uint64_t>(images, image.points.size());
        for (const auto& point : image.points) {
            append<double>(images, point[0]);
            append<double>(images, point[1]);
            append<int64_t>(images, -1);
        }
    }
    write_bytes(folder / "images.bin", images);
}

void expect_same_cameras(const std::vector<Camera>& a, const std::vector<Camera>& b, double tolerance) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(a[i].name);
        EXPECT_EQ(a[i].name, b[i].name);
        EXPECT_EQ(a[i].width, b[i].width);
        EXPECT_EQ(a[i].height, b[i].height);
        EXPECT_NEAR(a[i].fx, b[i].fx, tolerance);
        EXPECT_NEAR(a[i].fy, b[i].fy, tolerance);
        EXPECT_NEAR(a[i].cx, b[i].cx, tolerance);
        EXPECT_NEAR(a[i].cy, b[i].cy, tolerance);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(a[i].translation[c], b[i].translation[c], tolerance);
            for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[i].rotation[c][r], b[i].rotation[c][r], tolerance);
        }
    }
}

TEST(ColmapCameras, TextModel) {
    ScratchDir dir;
    write_text_model(dir.path());
    std::vector<std::string> warnings;
    const auto cameras = read_colmap_cameras(dir.path(), &warnings);
    ASSERT_EQ(cameras.size(), 6u);
    EXPECT_EQ(cameras[0].name, "a.png");  // sorted by name
    EXPECT_EQ(cameras[1].name, "b.png");
    EXPECT_EQ(cameras[2].name, "c.png");
    EXPECT_EQ(cameras[3].name, "d.png");

    // a.png: SIMPLE_RADIAL f cx cy k.
    EXPECT_EQ(cameras[0].width, 30);
    EXPECT_EQ(cameras[0].fx, 25);
    EXPECT_EQ(cameras[0].fy, 25);
    EXPECT_EQ(cameras[0].cx, 15);
    EXPECT_EQ(cameras[0].cy, 10);
    // b.png: OPENCV fx fy cx cy k1 k2 p1 p2.
    EXPECT_EQ(cameras[1].fx, 35);
    EXPECT_EQ(cameras[1].fy, 36);
    EXPECT_EQ(cameras[1].cx, 20);
    // c.png: PINHOLE, turned 90 degrees about z: world x becomes camera y; t is taken as is.
    const Camera& c = cameras[2];
    EXPECT_EQ(c.fy, 52);
    EXPECT_EQ(c.cy, 24);
    const glm::dvec3 x_axis = c.rotation * glm::dvec3(1, 0, 0);
    EXPECT_NEAR(x_axis.x, 0, 1e-12);
    EXPECT_NEAR(x_axis.y, 1, 1e-12);
    EXPECT_EQ(c.translation, glm::dvec3(1, 2, 3));
    // d.png: SIMPLE_PINHOLE f cx cy.
    EXPECT_EQ(cameras[3].fx, 14);
    EXPECT_EQ(cameras[3].fy, 14);
    EXPECT_EQ(cameras[3].cx, 8.5);
    EXPECT_EQ(cameras[3].cy, 6);
    // e.png: RADIAL f cx cy k1 k2; f.png: FULL_OPENCV fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6.
    EXPECT_EQ(cameras[4].fy, 30);
    EXPECT_EQ(cameras[4].cx, 16);
    EXPECT_EQ(cameras[5].fy, 41);
    EXPECT_EQ(cameras[5].cy, 18);

    // One per distorted COLMAP camera, by camera id, with its terms.
    ASSERT_EQ(warnings.size(), 4u);
    EXPECT_NE(warnings[0].find("camera 2 (SIMPLE_RADIAL k=0.01): distortion is ignored"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[1].find("camera 3 (OPENCV k1=0.1 k2=-0.05 p1=0.001 p2=0.002)"), std::string::npos)
        << warnings[1];
    EXPECT_NE(warnings[2].find("camera 5 (RADIAL k1=-0.05 k2=0.01)"), std::string::npos) << warnings[2];
    EXPECT_NE(warnings[3].find("camera 6 (FULL_OPENCV k1=-0.1 k2=0.02 p1=0.001 p2=-0.001 k3=0.003 k4=0.01 "
                               "k5=0.002 k6=0.001)"),
              std::string::npos)
        << warnings[3];
}

TEST(ColmapCameras, BinaryModelDecodesLikeTheText) {
    ScratchDir dir;
    write_text_model(dir / "text");
    write_binary_model(dir / "binary");
    std::vector<std::string> text_warnings, binary_warnings;
    const auto text = read_colmap_cameras(dir / "text", &text_warnings);
    const auto binary = read_colmap_cameras(dir / "binary", &binary_warnings);
    expect_same_cameras(text, binary, 0.0);
    EXPECT_EQ(binary_warnings.size(), text_warnings.size());
}

// A data folder undistorts its distorted cameras (undistort_test.cpp checks the photos), alike
// from text and binary models; its pinhole cameras stay exact.
TEST(ColmapCameras, ADataFolderUndistortsTextAndBinaryModelsAlike) {
    ScratchDir dir;
    write_text_model(dir / "text" / "sparse" / "0");
    write_binary_model(dir / "binary" / "sparse" / "0");
    for (const char* folder : {"text", "binary"})
        write_bytes(dir / folder / "sparse" / "0" / "points3D.txt", "1 0 0 0 255 0 0 0.5\n");
    const Dataset text = read_dataset(dir / "text", 0);
    const Dataset binary = read_dataset(dir / "binary", 0);
    expect_same_cameras(text.cameras, binary.cameras, 0.0);
    EXPECT_TRUE(text.warnings.empty());
    ASSERT_EQ(text.notices.size(), 4u);  // one per distorted COLMAP camera
    EXPECT_EQ(text.notices.size(), binary.notices.size());
    for (const char* model : {"SIMPLE_RADIAL", "OPENCV", "RADIAL", "FULL_OPENCV"}) {
        const auto said = std::count_if(text.notices.begin(), text.notices.end(), [&](const std::string& notice) {
            return notice.find(std::string("(") + model + " k") != std::string::npos &&
                   notice.find("photos undistorted to PINHOLE") != std::string::npos;
        });
        EXPECT_EQ(said, 1) << model;
    }
    const auto pinholes = read_colmap_cameras(dir / "text");
    for (size_t i = 0; i < pinholes.size(); ++i) {
        SCOPED_TRACE(pinholes[i].name);
        const bool distorted = pinholes[i].name == "a.png" || pinholes[i].name == "b.png" ||
                               pinholes[i].name == "e.png" || pinholes[i].name == "f.png";
        EXPECT_EQ(text.cameras[i].width, pinholes[i].width);
        EXPECT_EQ(text.cameras[i].fx != pinholes[i].fx, distorted);
        EXPECT_EQ(text.cameras[i].cx != pinholes[i].cx, distorted);
        EXPECT_EQ(text.cameras[i].rotation, pinholes[i].rotation);
    }
}

TEST(ColmapCameras, FindsTheModelInSparseZero) {
    ScratchDir dir;
    write_binary_model(dir / "sparse" / "0");
    EXPECT_EQ(read_colmap_cameras(dir.path()).size(), 6u);
    EXPECT_EQ(read_cameras(dir.path()).size(), 6u);
}

TEST(ColmapCameras, SnowmikuTextModelMatchesItsCamerasJson) {
    VKSPLAT_REQUIRE_SHARED_DATA();
    const auto scene = vksplat::test::shared_data_dir() / "snowmiku";
    std::vector<std::string> warnings;
    const auto colmap = read_colmap_cameras(scene / "sparse" / "0", &warnings);
    EXPECT_TRUE(warnings.empty());
    auto inria = read_inria_cameras(scene / "cameras.json");
    ASSERT_EQ(colmap.size(), 97u);
    std::sort(inria.begin(), inria.end(), [](const Camera& a, const Camera& b) { return a.name < b.name; });
    expect_same_cameras(colmap, inria, 1e-5);
}

TEST(ColmapCameras, Errors) {
    ScratchDir dir;
    expect_input_error([&] { read_colmap_cameras(dir / "none"); }, {"none", "no such folder"});
    expect_input_error([&] { read_colmap_cameras(dir.path()); }, {dir.path().string(), "no COLMAP model", "sparse/0"});

    write_text_model(dir / "fov");
    const std::string others = "5 PINHOLE 4 4 1 1 2 2\n6 PINHOLE 4 4 1 1 2 2\n";
    write_bytes(dir / "fov" / "cameras.txt",
                "2 FOV 30 20 25 15 10 0.01\n1 PINHOLE 64 48 50 52 32 24\n3 PINHOLE 4 4 1 1 2 2\n" + others);
    expect_input_error([&] { read_colmap_cameras(dir / "fov"); },
                       {"cameras.txt", "camera 2", "model FOV is not supported", "image_undistorter"});

    write_bytes(dir / "fov" / "cameras.txt", "1 PINHOLE 64 48 50 52 32 24\n3 PINHOLE 4 4 1 1 2 2\n" + others);
    expect_input_error([&] { read_colmap_cameras(dir / "fov"); }, {"images.txt", "'a.png'", "COLMAP camera 2"});

    write_bytes(dir / "fov" / "cameras.txt", "1 PINHOLE 64 48 fifty 52 32 24\n");
    expect_input_error([&] { read_colmap_cameras(dir / "fov"); }, {"cameras.txt", "line 1", "not a number"});

    write_bytes(dir / "fov" / "cameras.txt",
                "1 PINHOLE 64 48 50 52 32\n2 PINHOLE 4 4 1 1 2 2\n3 PINHOLE 4 4 1 1 2 2\n" + others);
    expect_input_error([&] { read_colmap_cameras(dir / "fov"); },
                       {"cameras.txt", "camera 1", "needs 4 parameters, got 3"});

    write_binary_model(dir / "cut");
    std::string images = read_bytes(dir / "cut" / "images.bin");
    images.resize(images.size() - 30);
    write_bytes(dir / "cut" / "images.bin", images);
    expect_input_error([&] { read_colmap_cameras(dir / "cut"); }, {"images.bin", "truncated", "image 5 of 6"});

    // A binary model's fisheye camera is refused by its name: camera 1, PINHOLE, made
    // SIMPLE_RADIAL_FISHEYE (model id 8, also 4 parameters).
    write_binary_model(dir / "fisheye");
    std::string cameras = read_bytes(dir / "fisheye" / "cameras.bin");
    const int32_t fisheye = 8;
    std::memcpy(&cameras[8 + 4], &fisheye, 4);  // the first camera's model id, after the count and its id
    write_bytes(dir / "fisheye" / "cameras.bin", cameras);
    expect_input_error([&] { read_colmap_cameras(dir / "fisheye"); },
                       {"cameras.bin", "camera 1", "model SIMPLE_RADIAL_FISHEYE is not supported"});
}

}  // namespace
}  // namespace vksplat::io::test
