#pragma once
// Shared by the io tests: a scratch folder per test, file helpers, generated clouds and an
// expectation that an InputError names the file and the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "vksplat/error.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::io::test {

// The SH degree-0 basis constant.
constexpr double kShC0 = 0.28209479177387814;

inline double sigmoid(double x) { return 1.0 / (1.0 + std::exp(-x)); }

// Appends `value`'s bytes as they are in memory (the test host is little-endian, as the formats are).
template <typename T>
void append(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
}

// A fresh folder for one test, removed with everything in it afterwards.
class ScratchDir {
public:
    ScratchDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string(info->test_suite_name()) + "_" + info->name();
        std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests are named "Suite/Test/0"
        std::random_device random;
        path_ = std::filesystem::temp_directory_path() / ("vksplat_io_" + name + "_" + std::to_string(random()));
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

inline std::string read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    return content.str();
}

// Runs `action`, which must throw InputError whose message contains every one of `parts`.
inline void expect_input_error(const std::function<void()>& action, const std::vector<std::string>& parts) {
    try {
        action();
        ADD_FAILURE() << "expected an InputError mentioning '" << (parts.empty() ? "" : parts[0]) << "'";
    } catch (const InputError& error) {
        const std::string message = error.what();
        for (const auto& part : parts)
            EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
}

// A cloud of `count` Gaussians with distinct, random values everywhere.
inline GaussianCloud random_cloud(size_t count, int sh_degree, unsigned seed = 1) {
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(count);
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> value(-3.0f, 3.0f);
    for (auto* values : {&cloud.positions, &cloud.log_scales, &cloud.rotations, &cloud.opacity_logits, &cloud.sh})
        for (float& v : *values) v = value(random);
    return cloud;
}

inline void expect_same_cloud(const GaussianCloud& a, const GaussianCloud& b) {
    ASSERT_EQ(a.sh_degree, b.sh_degree);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.log_scales, b.log_scales);
    EXPECT_EQ(a.rotations, b.rotations);
    EXPECT_EQ(a.opacity_logits, b.opacity_logits);
    EXPECT_EQ(a.sh, b.sh);
}

}  // namespace vksplat::io::test
