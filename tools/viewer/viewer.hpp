#pragma once
// `vksplat view`: a window showing a scene, rendered by vksplat's compute renderer into the
// swapchain through the embedding API (Renderer::record on an adopted device).
#include <array>
#include <optional>
#include <string>

namespace vksplat::viewer {

struct ViewerOptions {
    std::string scene;
    std::string cameras;                      // optional: dataset cameras to step through
    std::string compare;                      // optional: a second scene B toggles to (e.g. a pruned copy)
    std::optional<std::array<double, 3>> up;  // world up; default from the cameras, else +z
    int width = 1024, height = 768;           // initial window size
    std::array<float, 3> background{0, 0, 0};
    bool validation = false;
    bool hud = true;                          // start with the HUD's status line (H cycles it)
};

// Opens the window and runs until it is closed or Escape is pressed. Throws InputError for bad
// files and GpuError when there is no display, no Vulkan presentation, or no usable device.
int run_viewer(const ViewerOptions& options);

}  // namespace vksplat::viewer
