#pragma once
// A training data set on disk, read as it is: which of the three layouts people use it has, its
// cameras with the split the data gives them, its SfM points where it has any, where its photos
// are and which files were read. What to start training from, and which views to hold out where
// the data does not say, are the trainer's choices (jobs/train_scene.hpp), not the data's.
//
//   "colmap"          sparse/0 (or sparse) with cameras, images and points3D (.bin, .txt or
//                     .ply); photos in images/. Every test_every-th camera by image name is split
//                     "test", the rest "train" (the reference's llffhold); test_every 0: all "train".
//                     Cameras with lens distortion (SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV) come
//                     as PINHOLE cameras of their undistorted photos, which `undistortion` makes.
//   "nerf-synthetic"  transforms_train.json ("train") and, if present, transforms_test.json
//                     ("test"); photos beside them.
//   "inria"           cameras.json (with "split" fields where the file has them); photos in images/.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/io/image.hpp"
#include "vksplat/io/sfm_points.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::io {

// What turns the photos of a data set's cameras with lens distortion into the photos of the
// pinhole cameras the data set gives them (as COLMAP's image_undistorter does before the reference
// trains): per COLMAP camera, its lens and the pinhole chosen at load; each photo is remapped from
// the one to the other as it is read.
class PhotoUndistortion {
public:
    struct Lens;  // one COLMAP camera's photo size, lens and pinhole (src/io/undistort.hpp)

    PhotoUndistortion() = default;
    explicit PhotoUndistortion(std::map<std::string, std::shared_ptr<const Lens>> by_camera_name)
        : by_camera_name_(std::move(by_camera_name)) {}

    // `photo`, read from `file`, as the pinhole camera called `camera_name` sees it: as it is for
    // a camera without distortion. Throws InputError naming the file when the photo is not the
    // size its COLMAP camera gives.
    ImageRGB apply(const std::string& camera_name, ImageRGB photo, const std::filesystem::path& file) const;

private:
    std::map<std::string, std::shared_ptr<const Lens>> by_camera_name_;
};

struct Dataset {
    std::string format;                      // "colmap", "nerf-synthetic" or "inria"
    std::vector<Camera> cameras;             // Camera::split set where the layout says (above)
    std::optional<SfmPoints> points;         // COLMAP's points; the other layouts have none
    std::filesystem::path images_dir;        // where the layout keeps its photos (not checked here)
    std::vector<std::filesystem::path> files;  // the camera and point files read
    std::vector<std::string> warnings;       // what may be wrong with the data
    std::vector<std::string> notices;        // what was done to it: one line per COLMAP camera undistorted
    PhotoUndistortion undistortion;          // for the photos of cameras with lens distortion
};

// Throws InputError naming the folder when it holds none of the layouts, and the reader's
// InputError for a bad file.
Dataset read_dataset(const std::filesystem::path& folder, uint64_t test_every = 8);

// Writes cameras.json in the INRIA trainer's layout (what read_inria_cameras reads), each entry's
// "id" its index and "split" the camera's split where it has one.
void write_inria_cameras(const std::filesystem::path& path, const std::vector<Camera>& cameras,
                         WriteMode mode = WriteMode::refuse_existing);

}  // namespace vksplat::io
