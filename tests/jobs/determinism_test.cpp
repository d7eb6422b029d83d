// Repeated runs give the same answer: a frame does not depend on what the renderer drew before or on
// which renderer draws it (bit for bit: rgb, alpha, depth and contributor counts), and pruning with
// the random method keeps the same Gaussians for the same seed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "support/gpu_fixture.hpp"
#include "support/scenes.hpp"
#include "vksplat/io/ply.hpp"
#include "vksplat/jobs/prune_scene.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::test {
namespace {

namespace fs = std::filesystem;

void expect_bit_identical(const RenderOutput& a, const RenderOutput& b) {
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    // memcmp rather than ==, so that a NaN in both would still count as equal bits, and -0 != +0.
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float))) << "rgb differs";
    EXPECT_EQ(0, std::memcmp(a.alpha.data(), b.alpha.data(), a.alpha.size() * sizeof(float))) << "alpha differs";
    EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float))) << "depth differs";
    EXPECT_EQ(a.contributors, b.contributors);
}

class Determinism : public GpuTest {};

TEST_F(Determinism, SameViewIsBitIdenticalAfterOtherWorkAndWithAFreshRenderer) {
    const GaussianCloud scene = random_scene(81, 3000, 3, 2.0f, 8.0f, 0.01f, 0.4f);
    const Camera camera = forward_camera(150, 100, 110.0);
    const Camera other = Camera::look_at({1.0, -0.5, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 97, 61, 80.0, 80.0);

    Renderer first(context());
    first.set_scene(scene);
    const RenderOutput reference = first.render(camera);
    first.render(other);  // other sizes and buffer contents in between
    first.set_scene(random_scene(82, 500, 1));
    first.render(camera);
    first.set_scene(scene);
    expect_bit_identical(reference, first.render(camera));

    Renderer fresh(context());
    fresh.set_scene(scene);
    expect_bit_identical(reference, fresh.render(camera));
    // Gathering statistics does not change the picture.
    RenderSettings with_stats;
    with_stats.gather_stats = true;
    expect_bit_identical(reference, fresh.render(camera, with_stats));
}

class RandomPruneDeterminism : public GpuTest {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("vksplat_determinism_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    // The positions the pruned scene keeps (each Gaussian of the random scene has its own).
    std::vector<float> pruned_positions(uint64_t seed, const std::string& name) {
        Renderer renderer(context());
        std::vector<Camera> cameras;
        for (int i = 0; i < 3; ++i)
            cameras.push_back(Camera::look_at({0.3 * (i - 1), 0.0, 0.0}, {0.0, 0.0, 5.0}, {0.0, -1.0, 0.0}, 40, 32,
                                              40.0, 40.0));
        jobs::PruneOptions options;
        options.method = prune::ScoreMethod::random;
        options.selector = jobs::DropRatio{0.5};
        options.seed = seed;
        options.out = dir / name;
        const auto result = jobs::prune_scene(renderer, random_scene(83, 400, 1), cameras, options);
        EXPECT_LT(result.count_after, result.count_before);
        return io::read_ply(options.out).positions;
    }
    fs::path dir;
};

TEST_F(RandomPruneDeterminism, SameSeedKeepsTheSameGaussiansAndAnotherSeedOthers) {
    const auto a = pruned_positions(7, "a.ply");
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, pruned_positions(7, "b.ply"));
    EXPECT_NE(a, pruned_positions(8, "c.ply"));
}

}  // namespace
}  // namespace vksplat::test
