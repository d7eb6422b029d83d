#include "io/undistort.hpp"

#include <algorithm>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "vksplat/error.hpp"

namespace vksplat::io {
namespace detail {
namespace {

// The pinhole of a lens's undistorted photos, and what remaps the photos to it.
struct Undistorted {
    double fx, fy, cx, cy;
    std::shared_ptr<const PhotoUndistortion::Lens> remap;
};

Undistorted undistort_lens(const ColmapLens& lens) {
    // OpenCV puts pixel centres on whole numbers, COLMAP and vksplat at +0.5 (the top-left pixel's
    // centre is (0.5, 0.5)): the principal point moves by half a pixel into OpenCV and back.
    const cv::Matx33d distorted(lens.fx, 0, lens.cx - 0.5, 0, lens.fy, lens.cy - 0.5, 0, 0, 1);
    // OpenCV takes 4, 5, 8, 12 or 14 terms in COLMAP's order: SIMPLE_RADIAL's k and RADIAL's k1 k2
    // are its k1 (k2), with no tangential terms.
    std::vector<double> terms = lens.distortion;
    terms.resize(std::max<size_t>(terms.size(), 4), 0.0);
    const cv::Size size(lens.width, lens.height);
    // alpha 0: the new pinhole sees only pixels the photo has, so there is no blank border for
    // training to fit as black scene content; COLMAP's undistorter likewise keeps only valid pixels.
    // The size stays the photo's (COLMAP's keeps the focal length and changes the size instead), so
    // that cameras and photos on disk keep one size for every size check and --resolution-scale;
    // the focal length changes instead: for barrel distortion it shrinks (a wider view, the centre
    // sampled more coarsely; 12% for k1 = -0.18 at a 72 degree field), for pincushion it grows.
    // Each axis is fitted to its own valid extent, so a lens with fx = fy may come out with
    // fx != fy by a few percent; PINHOLE cameras carry both.
    // OpenCV (4.6) traces the photo's edge at 0..width, one pixel past the last pixel centre, which
    // leaves the right and bottom rims a pixel outside the photo; the extent of the pixel centres
    // keeps them in (undistort_test checks this).
    const cv::Size centres(std::max(1, lens.width - 1), std::max(1, lens.height - 1));
    const cv::Matx33d undistorted =
        cv::getOptimalNewCameraMatrix(distorted, terms, centres, 0.0, size, nullptr, false);
    auto remap = std::make_shared<PhotoUndistortion::Lens>(
        PhotoUndistortion::Lens{lens.width, lens.height, distorted, std::move(terms), undistorted});
    return {undistorted(0, 0), undistorted(1, 1), undistorted(0, 2) + 0.5, undistorted(1, 2) + 0.5, std::move(remap)};
}

}  // namespace

PhotoUndistortion undistort_cameras(ColmapCameras& model, std::vector<std::string>& notices) {
    std::map<uint32_t, Undistorted> by_id;
    for (const auto& [id, lens] : model.lenses) {
        if (!lens.distorted()) continue;
        const Undistorted& pinhole = by_id[id] = undistort_lens(lens);
        std::ostringstream notice;
        notice << model.cameras_file.string() << ": camera " << id << " (" << lens.description()
               << "): photos undistorted to PINHOLE fx=" << pinhole.fx << " fy=" << pinhole.fy << " cx=" << pinhole.cx
               << " cy=" << pinhole.cy << " at load (" << lens.width << "x" << lens.height << " kept, no blank border)";
        notices.push_back(notice.str());
    }
    std::map<std::string, std::shared_ptr<const PhotoUndistortion::Lens>> by_camera_name;
    for (size_t i = 0; i < model.cameras.size(); ++i) {
        const auto found = by_id.find(model.camera_ids[i]);
        if (found == by_id.end()) continue;
        Camera& camera = model.cameras[i];
        const Undistorted& pinhole = found->second;
        camera.fx = pinhole.fx;
        camera.fy = pinhole.fy;
        camera.cx = pinhole.cx;
        camera.cy = pinhole.cy;
        by_camera_name[camera.name] = pinhole.remap;
    }
    return PhotoUndistortion(std::move(by_camera_name));
}

}  // namespace detail

ImageRGB PhotoUndistortion::apply(const std::string& camera_name, ImageRGB photo,
                                  const std::filesystem::path& file) const {
    const auto found = by_camera_name_.find(camera_name);
    if (found == by_camera_name_.end()) return photo;
    const Lens& lens = *found->second;
    if (photo.width != lens.width || photo.height != lens.height)
        throw InputError(file.string(), "is " + std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                                            ", but the COLMAP camera of '" + camera_name + "' is " +
                                            std::to_string(lens.width) + "x" + std::to_string(lens.height) +
                                            ": its lens distortion cannot be taken out");
    cv::Mat map1, map2;  // fixed point: undistorted pixel -> position in the photo
    cv::initUndistortRectifyMap(lens.distorted, lens.terms, cv::noArray(), lens.undistorted,
                                cv::Size(lens.width, lens.height), CV_16SC2, map1, map2);
    cv::Mat source(photo.height, photo.width, CV_32FC3, photo.rgb.data());
    ImageRGB out{photo.width, photo.height, std::vector<float>(photo.rgb.size())};
    cv::Mat target(out.height, out.width, CV_32FC3, out.rgb.data());
    // Replicated edges only for the sub-pixel rim alpha 0's frame may reach past the photo.
    cv::remap(source, target, map1, map2, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    return out;
}

}  // namespace vksplat::io
