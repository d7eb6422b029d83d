#pragma once
// Renders a set of cameras to a folder: PNGs (8 or 16 bit), optional alpha PNGs and depth .npy,
// and, given the photos, PSNR/SSIM per view in metrics.csv. What `vksplat render` does.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vksplat/camera.hpp"
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
};

using Progress = std::function<void(size_t done, size_t total)>;

// The output stem of a camera: its name without folders or extension ("r_3.png" -> "r_3").
std::string output_stem(const Camera& camera, size_t index);

RenderViewsResult render_views(Renderer& renderer, const std::vector<Camera>& cameras,
                               const RenderViewsOptions& options, const Progress& progress = {});

}  // namespace vksplat::jobs
