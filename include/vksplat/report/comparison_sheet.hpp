#pragma once
// Comparison sheets: pictures of one view side by side on one row, each under a caption, e.g.
// photo | unpruned | pruned | error heat map, saved as one PNG.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/io/image.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::report {

struct SheetPanel {
    std::string caption;  // printed in a strip above the picture; ASCII (other bytes print as '?')
    int width = 0, height = 0;
    std::vector<float> rgb;  // row-major, 3 values per pixel, in [0, 1] (clamped; NaN shows as 0)
};

// The sheet as an image: panels left to right with no gap, so its width is the sum of the panel
// widths; its height is caption_strip_height(panels) plus the tallest panel. Shorter panels sit at
// the top of their column over a white background. Captions are dark text on white, centred over
// their panel, shrunk and then cut short with ".." when too long for it.
// Throws std::invalid_argument for no panels, or a panel whose size is not positive or whose rgb
// does not hold width * height * 3 values.
io::ImageRGB compose_comparison_sheet(const std::vector<SheetPanel>& panels);

// The height in pixels of the caption strip: it grows with the tallest panel, so that captions
// stay legible on large renders (24 px at most 400 px tall, up to 64 px).
int caption_strip_height(const std::vector<SheetPanel>& panels);

// Writes compose_comparison_sheet(panels) in the format the file's extension names: .png (8-bit
// RGB, lossless, through io::write_png_rgb) or .jpg / .jpeg (quality kJpegQuality: a sheet of lego's
// 800 x 800 renders weighs 0.3-0.45 MB, a third of its PNG). Throws InputError for any other
// extension.
void write_comparison_sheet(const std::filesystem::path& path, const std::vector<SheetPanel>& panels,
                            io::WriteMode mode);
inline constexpr int kJpegQuality = 85;

// A square of an image pair, e.g. where a pruned render differs most from the unpruned one.
struct ErrorWindow {
    int x = 0, y = 0, size = 0;  // top-left corner and side, in pixels, inside the image
    double mean_error = 0;       // mean over the window of eval::error_map(a, b)
};

// The size x size window (size clamped to the image's smaller side) with the largest mean absolute
// error between a and b (RGB, w x h); the first in row-major order on a tie. Throws
// std::invalid_argument for a size or image size that is not positive.
ErrorWindow largest_error_window(const float* a, const float* b, int w, int h, int size);

// A panel as tall as the pictures beside it (h) and half as wide, showing `window` of a (top) and
// of b (bottom) enlarged with nearest-neighbour pixels, so that single splats stay sharp: the place
// to look at, zoomed. Throws std::invalid_argument for a window outside the w x h image.
SheetPanel zoomed_window_panel(const float* a, const float* b, int w, int h, const ErrorWindow& window,
                               std::string caption);

// Draws the window's outline (2 px, inside the window) on a panel of the image's size.
void outline_window(SheetPanel& panel, const ErrorWindow& window, const std::array<float, 3>& colour);

// An error heat map of a against b (RGB, w x h, as eval::error_map sees them): the mean absolute
// error per pixel through eval::colorize_heat with max_error at the top of the ramp, followed on its
// right by a vertical colour bar (max_error at the top, 0 at the bottom) labelled 0, max/2 and max.
// The panel is w + heat_bar_width(h, max_error) wide and h tall; the map occupies its first w
// columns unchanged. Throws std::invalid_argument as error_map and colorize_heat do.
SheetPanel heat_map_panel(const float* a, const float* b, int w, int h, float max_error, std::string caption);

// The width of the colour bar heat_map_panel appends for a map h pixels tall.
int heat_bar_width(int h, float max_error);

}  // namespace vksplat::report
