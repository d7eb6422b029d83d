// COLMAP's text model: cameras.txt (one camera per line) and images.txt (two lines per image: the
// pose, then its 2D points, which may be an empty line). Lines starting with '#' are comments.
#include <fstream>
#include <sstream>

#include "io/colmap_model.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io::detail {
namespace {

std::ifstream open_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path.string(), std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    return in;
}

bool is_content(const std::string& line) {
    const size_t first = line.find_first_not_of(" \t\r");
    return first != std::string::npos && line[first] != '#';
}

}  // namespace

std::map<uint32_t, ColmapIntrinsics> read_colmap_cameras_text(const std::filesystem::path& path) {
    std::ifstream in = open_text(path);
    std::map<uint32_t, ColmapIntrinsics> cameras;
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (!is_content(line)) continue;
        std::istringstream fields(line);
        uint32_t id = 0;
        ColmapIntrinsics camera;
        if (!(fields >> id >> camera.model >> camera.width >> camera.height))
            throw InputError(path.string(),
                             "line " + std::to_string(number) + ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
        for (double param; fields >> param;) camera.params.push_back(param);
        if (!fields.eof())
            throw InputError(path.string(), "line " + std::to_string(number) + ": a camera parameter is not a number");
        if (!cameras.emplace(id, std::move(camera)).second)
            throw InputError(path.string(),
                             "line " + std::to_string(number) + ": camera " + std::to_string(id) + " is defined twice");
    }
    return cameras;
}

std::vector<ColmapImage> read_colmap_images_text(const std::filesystem::path& path) {
    std::ifstream in = open_text(path);
    std::vector<ColmapImage> images;
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (!is_content(line)) continue;
        std::istringstream fields(line);
        uint32_t image_id = 0;
        ColmapImage image;
        if (!(fields >> image_id >> image.qvec[0] >> image.qvec[1] >> image.qvec[2] >> image.qvec[3] >> image.tvec[0] >>
              image.tvec[1] >> image.tvec[2] >> image.camera_id))
            throw InputError(path.string(), "line " + std::to_string(number) +
                                                ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
        std::getline(fields >> std::ws, image.name);
        while (!image.name.empty() && (image.name.back() == '\r' || image.name.back() == ' ')) image.name.pop_back();
        if (image.name.empty())
            throw InputError(path.string(),
                             "line " + std::to_string(number) + ": image " + std::to_string(image_id) + " has no name");
        images.push_back(std::move(image));
        // The next line lists the image's 2D points, which a camera does not need.
        if (std::getline(in, line)) ++number;
    }
    return images;
}

void read_colmap_points_text(const std::filesystem::path& path, std::vector<float>& positions,
                             std::vector<float>& colors) {
    std::ifstream in = open_text(path);
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (!is_content(line)) continue;
        std::istringstream fields(line);
        uint64_t id = 0;
        double x, y, z;
        int r, g, b;
        if (!(fields >> id >> x >> y >> z >> r >> g >> b) || r < 0 || r > 255 || g < 0 || g > 255 || b < 0 || b > 255)
            throw InputError(path.string(), "line " + std::to_string(number) +
                                                ": expected POINT3D_ID X Y Z R G B (colours 0..255) ERROR TRACK[]");
        for (double v : {x, y, z}) positions.push_back(static_cast<float>(v));
        for (int v : {r, g, b}) colors.push_back(float(v) / 255.0f);
    }
}

}  // namespace vksplat::io::detail
