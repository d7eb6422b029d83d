// Photos of COLMAP cameras with lens distortion come out of a data set as the photos of pinholes:
// straight lines drawn through a pinhole and distorted here with COLMAP's equations for each
// model (written out below, not OpenCV's undistortion) are straight again, where the new pinhole
// says, once the data set has read them; and that pinhole sees no pixel the photo lacks.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/dataset.hpp"
#include "vksplat/io/image.hpp"

namespace vksplat::io::test {
namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr double kLineSpacing = 16, kLineSigma = 1.2;  // ideal pixels

struct Lens {
    const char* model;
    std::vector<double> params;  // COLMAP's, in its order
};

// Focal lengths, principal point (COLMAP's pixel convention) and distortion terms of a lens.
struct Parts {
    double fx, fy, cx, cy;
    double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0, k4 = 0, k5 = 0, k6 = 0;
};

Parts parts_of(const Lens& lens) {
    const auto& p = lens.params;
    const std::string model = lens.model;
    if (model == "SIMPLE_RADIAL") return {p[0], p[0], p[1], p[2], p[3]};
    if (model == "RADIAL") return {p[0], p[0], p[1], p[2], p[3], p[4]};
    if (model == "OPENCV") return {p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]};
    return {p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11]};  // FULL_OPENCV
}

// COLMAP's forward model on normalised image coordinates (OpenCVCameraModel / FullOpenCVCameraModel;
// SIMPLE_RADIAL and RADIAL are the same with the other terms 0).
std::array<double, 2> distort(const Parts& d, double u, double v) {
    const double r2 = u * u + v * v;
    const double radial =
        (1 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3))) / (1 + r2 * (d.k4 + r2 * (d.k5 + r2 * d.k6)));
    return {u * radial + 2 * d.p1 * u * v + d.p2 * (r2 + 2 * u * u),
            v * radial + d.p1 * (r2 + 2 * v * v) + 2 * d.p2 * u * v};
}

// The normalised coordinates that distort() takes to (ud, vd), by fixed-point iteration.
std::array<double, 2> undistort(const Parts& d, double ud, double vd) {
    double u = ud, v = vd;
    for (int i = 0; i < 50; ++i) {
        const auto [du, dv] = distort(d, u, v);
        u += ud - du;
        v += vd - dv;
    }
    return {u, v};
}

// A grid of thin lines as the pinhole (fx, fy, cx, cy) sees it: vertical lines (red) at
// x = cx + n * kLineSpacing, horizontal ones (green) at y = cy + n * kLineSpacing.
std::array<double, 2> grid(double x, double y, double cx, double cy) {
    const auto line = [](double offset) {
        const double d = offset - kLineSpacing * std::round(offset / kLineSpacing);
        return std::exp(-d * d / (2 * kLineSigma * kLineSigma));
    };
    return {line(x - cx), line(y - cy)};
}

// The photo the distorted lens takes of that grid (4x4 samples a pixel).
std::vector<float> distorted_photo(const Parts& lens) {
    std::vector<float> rgb(size_t(kWidth) * kHeight * 3, 0.0f);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            for (int s = 0; s < 16; ++s) {
                const double x = i + (s % 4 + 0.5) / 4, y = j + (s / 4 + 0.5) / 4;
                const auto [u, v] = undistort(lens, (x - lens.cx) / lens.fx, (y - lens.cy) / lens.fy);
                const auto [red, green] = grid(lens.fx * u + lens.cx, lens.fy * v + lens.cy, lens.cx, lens.cy);
                rgb[(size_t(j) * kWidth + i) * 3 + 0] += float(red / 16);
                rgb[(size_t(j) * kWidth + i) * 3 + 1] += float(green / 16);
            }
    return rgb;
}

// A COLMAP data folder of one camera with `lens`, its photo view.png.
void write_data_folder(const std::filesystem::path& folder, const Lens& lens, const std::vector<float>& photo) {
    std::filesystem::create_directories(folder / "sparse" / "0");
    std::filesystem::create_directories(folder / "images");
    std::ofstream cameras(folder / "sparse" / "0" / "cameras.txt");
    cameras.precision(17);
    cameras << "1 " << lens.model << ' ' << kWidth << ' ' << kHeight;
    for (double p : lens.params) cameras << ' ' << p;
    cameras << '\n';
    std::ofstream(folder / "sparse" / "0" / "images.txt") << "1 1 0 0 0 0 0 0 1 view.png\n\n";
    std::ofstream(folder / "sparse" / "0" / "points3D.txt") << "1 0 0 1 255 255 255 0.5\n";
    write_png_rgb(folder / "images" / "view.png", kWidth, kHeight, photo.data(), 16);
}

struct LineFit {
    double worst_residual = 0;  // px from the straight line fitted through the line's centres
    double worst_offset = 0;    // px from where the pinhole puts the line
};

// The lines of one channel, expected at first + n * step (columns when vertical, rows when not):
// each line's centre in every row (column), how far those stray from a straight line fitted
// through them and from where the line is expected.
LineFit fit_lines(const ImageRGB& image, int channel, bool vertical, double first, double step) {
    const int length = vertical ? image.height : image.width, span = vertical ? image.width : image.height;
    const auto value = [&](int along, int at) {
        const int x = vertical ? at : along, y = vertical ? along : at;
        return double(image.rgb[(size_t(y) * image.width + x) * 3 + channel]);
    };
    LineFit fit;
    for (double expected = first - step * std::floor(first / step); expected < span; expected += step) {
        if (expected < 6 || expected > span - 6) continue;  // a line must lie whole inside its window
        std::vector<double> positions, centres;
        for (int along = 2; along < length - 2; ++along) {
            double sum = 0, weighted = 0;
            for (int at = int(expected) - 4; at <= int(expected) + 4; ++at) {
                sum += value(along, at);
                weighted += value(along, at) * (at + 0.5);
            }
            positions.push_back(along + 0.5);
            centres.push_back(weighted / sum);
        }
        double mp = 0, mc = 0;
        for (size_t i = 0; i < centres.size(); ++i) mp += positions[i], mc += centres[i];
        mp /= double(centres.size()), mc /= double(centres.size());
        double spp = 0, spc = 0;
        for (size_t i = 0; i < centres.size(); ++i) {
            spp += (positions[i] - mp) * (positions[i] - mp);
            spc += (positions[i] - mp) * (centres[i] - mc);
        }
        const double slope = spc / spp;
        for (size_t i = 0; i < centres.size(); ++i) {
            fit.worst_residual = std::max(fit.worst_residual, std::abs(centres[i] - (mc + slope * (positions[i] - mp))));
            fit.worst_offset = std::max(fit.worst_offset, std::abs(centres[i] - expected));
        }
    }
    return fit;
}

class UndistortedLines : public ::testing::TestWithParam<Lens> {};

TEST_P(UndistortedLines, StraightLinesComeOutStraightWhereThePinholeSays) {
    const Lens& lens = GetParam();
    const Parts parts = parts_of(lens);
    const ScratchDir dir;
    write_data_folder(dir.path(), lens, distorted_photo(parts));
    const Dataset data = read_dataset(dir.path(), 0);
    ASSERT_EQ(data.cameras.size(), 1u);
    const Camera& camera = data.cameras[0];
    EXPECT_EQ(camera.width, kWidth);
    EXPECT_EQ(camera.height, kHeight);
    ASSERT_EQ(data.notices.size(), 1u);
    EXPECT_NE(data.notices[0].find(std::string("camera 1 (") + lens.model + " k"), std::string::npos) << data.notices[0];
    EXPECT_NE(data.notices[0].find("photos undistorted to PINHOLE fx="), std::string::npos) << data.notices[0];
    EXPECT_TRUE(data.warnings.empty());

    const auto file = find_image(data.images_dir, camera.name);
    const ImageRGB photo = read_image_rgb(file, {0, 0, 0});
    const ImageRGB undistorted = data.undistortion.apply(camera.name, photo, file);
    ASSERT_EQ(undistorted.width, kWidth);
    ASSERT_EQ(undistorted.height, kHeight);
    // Where the pinhole puts the grid's lines: the ideal pinhole's x = cx + n * spacing, seen by
    // the new focal length from the new principal point.
    const double first_x = camera.cx, step_x = kLineSpacing * camera.fx / parts.fx;
    const double first_y = camera.cy, step_y = kLineSpacing * camera.fy / parts.fy;
    for (const bool vertical : {true, false}) {
        SCOPED_TRACE(vertical ? "vertical lines" : "horizontal lines");
        const int channel = vertical ? 0 : 1;
        const LineFit fit = fit_lines(undistorted, channel, vertical, vertical ? first_x : first_y,
                                      vertical ? step_x : step_y);
        EXPECT_LT(fit.worst_residual, 0.5);  // measured: 0.065 px at most
        // Measured 0.055 px at most; the principal point half a pixel off (OpenCV's pixel centres
        // taken for COLMAP's) puts lines 0.10-0.38 px off.
        EXPECT_LT(fit.worst_offset, 0.1);
        // The photo as taken: the same lines, before undistortion, are bent by 1.2-6.5 px, so the
        // check above can fail.
        const LineFit bent = fit_lines(photo, channel, vertical, vertical ? parts.cx : parts.cy, kLineSpacing);
        EXPECT_GT(bent.worst_residual, 1.0);
    }

    // The new pinhole sees no pixel the photo lacks (no blank border), and crops no more than
    // that needs: the centres of its frame's outer pixels, distorted, lie within the centres of
    // the photo's outer pixels (where interpolation has pixels on both sides) and reach them.
    double margin = 1e9;
    for (int s = 0; s <= 400; ++s) {
        const double x = 0.5 + s * (kWidth - 1) / 400.0, y = 0.5 + s * (kHeight - 1) / 400.0;
        for (const auto [fx, fy] : {std::array<double, 2>{x, 0.5}, {x, kHeight - 0.5}, {0.5, y}, {kWidth - 0.5, y}}) {
            const auto [u, v] = distort(parts, (fx - camera.cx) / camera.fx, (fy - camera.cy) / camera.fy);
            const double px = parts.fx * u + parts.cx, py = parts.fy * v + parts.cy;
            margin = std::min({margin, px - 0.5, py - 0.5, kWidth - 0.5 - px, kHeight - 0.5 - py});
        }
    }
    EXPECT_GT(margin, -0.1);  // measured: -0.002 at worst; OpenCV's own frame was a pixel out
    EXPECT_LT(margin, 0.5);
}

INSTANTIATE_TEST_SUITE_P(
    ColmapModels, UndistortedLines,
    ::testing::Values(Lens{"SIMPLE_RADIAL", {110, 81.3, 58.7, -0.18}}, Lens{"RADIAL", {110, 79.6, 61.2, -0.2, 0.06}},
                      Lens{"OPENCV", {112, 108, 80.7, 59.4, -0.22, 0.05, 0.003, -0.002}},
                      Lens{"OPENCV", {112, 108, 78.2, 60.9, 0.25, 0.04, -0.002, 0.003}},  // pincushion
                      Lens{"FULL_OPENCV", {112, 108, 80.7, 59.4, -0.2, 0.04, 0.002, -0.003, 0.01, 0.05, 0, 0.01}}),
    [](const auto& info) { return std::string(info.param.model) + "_" + std::to_string(info.index); });

TEST(Undistortion, ALensWithoutDistortionIsLeftAsItIs) {
    const ScratchDir dir;
    std::vector<float> photo(size_t(kWidth) * kHeight * 3);
    for (size_t i = 0; i < photo.size(); ++i) photo[i] = float(i % 251) / 250;
    write_data_folder(dir.path(), {"SIMPLE_RADIAL", {110, 81.3, 58.7, 0}}, photo);
    const Dataset data = read_dataset(dir.path(), 0);
    EXPECT_TRUE(data.notices.empty());
    EXPECT_EQ(data.cameras[0].fx, 110);
    EXPECT_EQ(data.cameras[0].cx, 81.3);
    const auto file = find_image(data.images_dir, "view.png");
    const ImageRGB read = read_image_rgb(file, {0, 0, 0});
    EXPECT_EQ(data.undistortion.apply("view.png", read, file).rgb, read.rgb);
}

TEST(Undistortion, APhotoOfAnotherSizeIsRefused) {
    const ScratchDir dir;
    write_data_folder(dir.path(), {"RADIAL", {110, 79.6, 61.2, -0.2, 0.06}}, std::vector<float>(kWidth * kHeight * 3));
    const Dataset data = read_dataset(dir.path(), 0);
    const ImageRGB small{kWidth / 2, kHeight / 2, std::vector<float>(kWidth * kHeight * 3 / 4)};
    expect_input_error([&] { data.undistortion.apply("view.png", small, dir / "view.png"); },
                       {"view.png", "is 80x60, but the COLMAP camera of 'view.png' is 160x120"});
}

TEST(Undistortion, AModelWithoutUndistortionIsRefusedByName) {
    const ScratchDir dir;
    write_data_folder(dir.path(), {"OPENCV_FISHEYE", {110, 110, 80, 60, 0.1, 0, 0, 0}},
                      std::vector<float>(kWidth * kHeight * 3));
    expect_input_error([&] { read_dataset(dir.path()); },
                       {"cameras.txt", "camera 1", "camera model OPENCV_FISHEYE is not supported"});
}

}  // namespace
}  // namespace vksplat::io::test
