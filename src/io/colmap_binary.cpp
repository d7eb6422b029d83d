// COLMAP's binary model (little-endian): cameras.bin, images.bin and points3D.bin as COLMAP's
// WriteCamerasBinary/WriteImagesBinary/WritePoints3DBinary lay them out.
#include <fstream>

#include "io/byte_order.hpp"
#include "io/colmap_model.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io::detail {
namespace {

constexpr const char* kModelNames[] = {"SIMPLE_PINHOLE",
                                       "PINHOLE",
                                       "SIMPLE_RADIAL",
                                       "RADIAL",
                                       "OPENCV",
                                       "OPENCV_FISHEYE",
                                       "FULL_OPENCV",
                                       "FOV",
                                       "SIMPLE_RADIAL_FISHEYE",
                                       "RADIAL_FISHEYE",
                                       "THIN_PRISM_FISHEYE"};
constexpr size_t kModelParamCounts[] = {3, 4, 4, 5, 8, 8, 12, 5, 4, 5, 12};

// Reads fields in order, and says where the file ended if it ends too soon.
class BinaryFile {
public:
    explicit BinaryFile(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {
        if (!in_) throw InputError(path.string(), std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    }

    template <typename T>
    T read(const std::string& what) {
        char bytes[sizeof(T)];
        if (!in_.read(bytes, sizeof(T))) throw truncated(what);
        return load_little_endian<T>(bytes);
    }
    std::string read_name(const std::string& what) {
        std::string name;
        if (!std::getline(in_, name, '\0')) throw truncated(what);
        return name;
    }
    void skip(uint64_t count, uint64_t size, const std::string& what) {
        const uint64_t left = std::filesystem::file_size(path_) - static_cast<uint64_t>(in_.tellg());
        if (count > left / size) throw truncated(what);
        in_.ignore(static_cast<std::streamsize>(count * size));
    }

private:
    InputError truncated(const std::string& what) {
        in_.clear();
        return InputError(path_.string(),
                          "truncated: the file ends at byte " + std::to_string(in_.tellg()) + " inside " + what);
    }

    std::filesystem::path path_;
    std::ifstream in_;
};

// COLMAP's name for a model id (the binary files store ids), or "" for an unknown id.
std::string colmap_model_name(int64_t id) {
    return id >= 0 && id < static_cast<int64_t>(std::size(kModelNames)) ? kModelNames[id] : "";
}

}  // namespace

std::map<uint32_t, ColmapIntrinsics> read_colmap_cameras_binary(const std::filesystem::path& path) {
    BinaryFile file(path);
    const auto count = file.read<uint64_t>("the camera count");
    std::map<uint32_t, ColmapIntrinsics> cameras;
    for (uint64_t index = 0; index < count; ++index) {
        const std::string what = "camera " + std::to_string(index) + " of " + std::to_string(count);
        const auto id = file.read<uint32_t>(what);
        const auto model_id = file.read<int32_t>(what);
        ColmapIntrinsics camera;
        camera.model = colmap_model_name(model_id);
        if (camera.model.empty())
            throw InputError(path.string(),
                             "camera " + std::to_string(id) + " has unknown model id " + std::to_string(model_id));
        camera.width = file.read<uint64_t>(what);
        camera.height = file.read<uint64_t>(what);
        for (size_t p = 0; p < kModelParamCounts[model_id]; ++p) camera.params.push_back(file.read<double>(what));
        if (!cameras.emplace(id, std::move(camera)).second)
            throw InputError(path.string(), "camera " + std::to_string(id) + " is defined twice");
    }
    return cameras;
}

std::vector<ColmapImage> read_colmap_images_binary(const std::filesystem::path& path) {
    BinaryFile file(path);
    const auto count = file.read<uint64_t>("the image count");
    std::vector<ColmapImage> images;
    for (uint64_t index = 0; index < count; ++index) {
        const std::string what = "image " + std::to_string(index) + " of " + std::to_string(count);
        ColmapImage image;
        file.read<uint32_t>(what);  // the image id: cameras are identified by name instead
        for (double& q : image.qvec) q = file.read<double>(what);
        for (double& t : image.tvec) t = file.read<double>(what);
        image.camera_id = file.read<uint32_t>(what);
        image.name = file.read_name(what);
        // Its 2D points (x, y as doubles, point id as int64), which a camera does not need.
        file.skip(file.read<uint64_t>(what), 24, what);
        images.push_back(std::move(image));
    }
    return images;
}

void read_colmap_points_binary(const std::filesystem::path& path, std::vector<float>& positions,
                               std::vector<float>& colors) {
    BinaryFile file(path);
    const auto count = file.read<uint64_t>("the point count");
    for (uint64_t index = 0; index < count; ++index) {
        const std::string what = "point " + std::to_string(index) + " of " + std::to_string(count);
        file.read<uint64_t>(what);  // the point id
        for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(file.read<double>(what)));
        for (int k = 0; k < 3; ++k) colors.push_back(float(file.read<uint8_t>(what)) / 255.0f);
        file.read<double>(what);  // the reprojection error
        // Its track (image id, 2D point index as int32 each), which initialisation does not need.
        file.skip(file.read<uint64_t>(what), 8, what);
    }
}

}  // namespace vksplat::io::detail
