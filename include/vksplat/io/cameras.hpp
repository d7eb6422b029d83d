#pragma once
// Camera files: INRIA cameras.json, COLMAP sparse models and NeRF transforms files. Every reader
// returns cameras with OpenCV axes and a world-to-camera transform, checked with Camera::validate();
// errors are InputError naming the file and the camera (index and name) at fault.
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::io {

// INRIA trainer's cameras.json: a list of {id, img_name, width, height, position, rotation, fx, fy}
// and optional cx, cy (default: the image centre). `rotation` is camera-to-world, given as rows;
// `position` is the camera centre. Cameras keep the file's order; name = img_name, split = the
// optional "split".
std::vector<Camera> read_inria_cameras(const std::filesystem::path& path);

// A COLMAP model: `dir` holds cameras.bin + images.bin or cameras.txt + images.txt, or has them in
// dir/sparse/0 or dir/0. Models PINHOLE and SIMPLE_PINHOLE are exact; SIMPLE_RADIAL, RADIAL, OPENCV
// and FULL_OPENCV are read as pinholes, with a warning per COLMAP camera that its distortion is
// ignored (read_dataset undistorts them instead); other models are refused, by name.
// Cameras are sorted by image name; name = the image's name.
std::vector<Camera> read_colmap_cameras(const std::filesystem::path& dir, std::vector<std::string>* warnings = nullptr);

// A NeRF transforms_*.json: camera_angle_x (and optional camera_angle_y, cx, cy, w, h) and
// frames[] of {file_path, transform_matrix}, the matrix camera-to-world with OpenGL axes. Without
// w/h the image size is read from the image (file_path, with ".png" added if it has no extension,
// relative to the file's folder). name = file_path.
std::vector<Camera> read_nerf_transforms(const std::filesystem::path& path);

// Picks the format: a folder is a COLMAP model; a .json holding a list is INRIA's, one holding an
// object with "frames" is NeRF's.
std::vector<Camera> read_cameras(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);

// The photo of the camera called `name` in `images_dir`: the exact name, else the name with .png,
// .jpg, .jpeg, .JPG or .PNG added, else the one file whose stem is the name's stem. Throws InputError
// listing where it looked.
std::filesystem::path find_image(const std::filesystem::path& images_dir, const std::string& name);

}  // namespace vksplat::io
