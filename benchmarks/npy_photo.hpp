#pragma once
// The GPU-host benchmarks' photos: <image stem>.npy, uint8 [H, W, 3], made on the host by
// benchmarks/photos_to_npy.py, since those hosts have no image codecs vksplat links.
#include <filesystem>

#include "vksplat/camera/camera.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::bench {

inline io::ImageRGB read_npy_photo(const std::filesystem::path& folder, const Camera& camera) {
    const auto path = folder / (std::filesystem::path(camera.name).stem().string() + ".npy");
    const io::NpyArray array = io::read_npy(path);
    if (array.shape.size() != 3 || array.shape[2] != 3) throw InputError(path.string(), "expected uint8 [H, W, 3]");
    const auto bytes = array.values<uint8_t>();
    io::ImageRGB image{int(array.shape[1]), int(array.shape[0]), std::vector<float>(bytes.size())};
    for (size_t i = 0; i < bytes.size(); ++i) image.rgb[i] = float(bytes[i]) / 255.0f;
    return image;
}

}  // namespace vksplat::bench
