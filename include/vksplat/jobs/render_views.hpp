#pragma once
// Renders a set of cameras to a folder: PNGs (8 or 16 bit), optional alpha PNGs and depth .npy,
// and, given the photos, PSNR/SSIM per view in metrics.csv. What `vksplat render` does.
//
// Each view's files are named after its camera (output_stems): <stem>.png, <stem>.alpha.png,
// <stem>.depth.npy. Every file is checked before the first is written: none may exist (unless
// mode says overwrite), none may be one of the photos or other inputs, no two may share a name.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/io/write_mode.hpp"
#include "vksplat/render/renderer.hpp"

namespace vksplat::jobs {

struct RenderViewsOptions {
    std::filesystem::path out_dir;
    std::vector<size_t> views;  // indices into the cameras; empty = all
    RenderSettings settings;
    int bit_depth = 8;          // 8 or 16
    bool write_alpha = false;   // <name>.alpha.png, 16-bit grey
    bool write_depth = false;   // <name>.depth.npy, float32 H x W
    std::optional<std::filesystem::path> images_dir;  // photos to score against
    io::WriteMode mode = io::WriteMode::refuse_existing;
    // The files the scene and cameras were read from: no output may be one of them (nor one of
    // the photos), whatever the mode.
    std::vector<std::filesystem::path> inputs;
};

struct ViewResult {
    size_t index = 0;
    std::string name;             // output stem
    std::filesystem::path image;
    double psnr = 0, ssim = 0;    // against the photo, when images_dir is set
    double gpu_milliseconds = 0;
};

struct RenderViewsResult {
    std::vector<ViewResult> views;
    bool has_metrics = false;
    double mean_psnr = 0, mean_ssim = 0;
    std::filesystem::path metrics_csv;
    std::vector<std::filesystem::path> files;  // every file written, in the order written
};

using Progress = std::function<void(size_t done, size_t total)>;

// The output stem of every camera, distinct within the list: its name without folders or
// extension ("images/r_3.png" -> "r_3"), "view_0007" for camera 7 if it has no name. Where stems
// coincide (a name given twice, or "a/x.jpg" and "b/x.jpg"), the first camera in the list keeps
// the plain stem and the later ones get "-2", "-3", ... ("x", "x-2", "x-3"), skipping stems that
// other cameras have. A camera's stem depends on the whole list only, never on which views are
// rendered, so a file keeps its name from one run to the next.
std::vector<std::string> output_stems(const std::vector<Camera>& cameras);

// Throws InputError, before anything is rendered or written, for a view index out of range or
// given twice, a missing photo, or an output that may not be written (see above).
RenderViewsResult render_views(Renderer& renderer, const std::vector<Camera>& cameras,
                               const RenderViewsOptions& options, const Progress& progress = {});

}  // namespace vksplat::jobs
