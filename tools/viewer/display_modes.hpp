#pragma once
// The ways the viewer can draw a scene, made by changing a copy of the cloud rather than the
// renderer: a splat-scale factor (the reference viewer's scale modifier), Gaussians as small
// round dots where their centres are (to see where they sit), and every Gaussian opaque (to see
// their shapes as solid ellipsoids).
#include "vksplat/scene/scene.hpp"

namespace vksplat::viewer {

enum class DisplayMode { splats, points, ellipsoids };

const char* to_string(DisplayMode mode);
DisplayMode next(DisplayMode mode);

// `scene` as `mode` draws it: scales times `scale` (splats, ellipsoids), or every Gaussian a dot
// of standard deviation point_size (points); opacity 0.99 for points and ellipsoids.
GaussianCloud display_cloud(const GaussianCloud& scene, DisplayMode mode, double scale, double point_size);

}  // namespace vksplat::viewer
