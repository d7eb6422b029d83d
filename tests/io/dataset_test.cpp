// Training data sets on disk: each layout read with the split its data gives, and the INRIA
// cameras.json a training run writes read back as it was written.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <glm/gtc/quaternion.hpp>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/dataset.hpp"

namespace vksplat::io::test {
namespace {

std::vector<Camera> ring(int count) {
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * M_PI * i / count;
        Camera camera = Camera::look_at({4.0 * std::sin(angle), 0.5, -4.0 * std::cos(angle)}, {0.0, 0.0, 0.0},
                                        {0.0, -1.0, 0.0}, 64, 48, 50.0, 52.0);
        camera.name = "view_" + std::to_string(10 + i) + ".png";
        cameras.push_back(camera);
    }
    return cameras;
}

TEST(Dataset, AColmapFolderIsSplitEveryNthByName) {
    const ScratchDir dir;
    std::filesystem::create_directories(dir.path() / "sparse" / "0");
    std::filesystem::create_directories(dir.path() / "images");
    const auto cameras = ring(10);
    std::ofstream(dir.path() / "sparse" / "0" / "cameras.txt") << "1 PINHOLE 64 48 50 52 32 24\n";
    {
        std::ofstream images(dir.path() / "sparse" / "0" / "images.txt");
        images.precision(12);
        for (size_t i = 0; i < cameras.size(); ++i) {
            const glm::dquat q = glm::quat_cast(cameras[i].rotation);
            const glm::dvec3 t = cameras[i].translation;
            images << i + 1 << ' ' << q.w << ' ' << q.x << ' ' << q.y << ' ' << q.z << ' ' << t.x << ' ' << t.y << ' '
                   << t.z << " 1 " << cameras[i].name << "\n\n";
        }
    }
    std::ofstream(dir.path() / "sparse" / "0" / "points3D.txt") << "1 0 0 0 255 0 0 0.5\n2 0.1 0 0 0 255 0 0.5\n";
    const Dataset data = read_dataset(dir.path(), 4);
    EXPECT_EQ(data.format, "colmap");
    ASSERT_EQ(data.cameras.size(), 10u);
    for (size_t i = 0; i < 10; ++i) EXPECT_EQ(data.cameras[i].split, i % 4 == 0 ? "test" : "train") << i;
    ASSERT_TRUE(data.points.has_value());
    EXPECT_EQ(data.points->size(), 2u);
    EXPECT_EQ(data.files.size(), 3u);
    EXPECT_EQ(data.images_dir, dir.path() / "images");
    for (const Camera& camera : read_dataset(dir.path(), 0).cameras) EXPECT_EQ(camera.split, "train");
}

TEST(Dataset, NamesAFolderOfNoKnownLayout) {
    const ScratchDir dir;
    expect_input_error([&] { read_dataset(dir.path()); }, {dir.path().string(), "holds neither a COLMAP model"});
    expect_input_error([&] { read_dataset(dir / "absent"); }, {"absent", "is not a folder"});
}

TEST(Dataset, InriaCamerasWrittenReadBackAsTheyWere) {
    const ScratchDir dir;
    auto cameras = ring(5);
    cameras[1].split = "test";
    cameras[2].split = "train";
    write_inria_cameras(dir / "cameras.json", cameras);
    std::filesystem::create_directories(dir.path() / "images");
    const Dataset data = read_dataset(dir.path());
    EXPECT_EQ(data.format, "inria");
    ASSERT_EQ(data.cameras.size(), cameras.size());
    for (size_t i = 0; i < cameras.size(); ++i) {
        const Camera &a = cameras[i], &b = data.cameras[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.split, b.split);
        EXPECT_EQ(a.width, b.width);
        EXPECT_DOUBLE_EQ(a.fy, b.fy);
        EXPECT_NEAR(glm::length(a.centre() - b.centre()), 0.0, 1e-12);
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) EXPECT_NEAR(a.rotation[c][r], b.rotation[c][r], 1e-12);
    }
    expect_input_error([&] { write_inria_cameras(dir / "cameras.json", cameras); }, {"cameras.json", "already exists"});
}

}  // namespace
}  // namespace vksplat::io::test
