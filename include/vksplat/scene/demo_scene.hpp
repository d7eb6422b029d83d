#pragma once
// A small scene made by code, for examples, benchmarks and tests that need no data files, and
// cameras that orbit it.
#include "vksplat/camera/camera.hpp"
#include "vksplat/scene/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vksplat {

// The demo scene's parts, stored one after another in this order (so a test can tell them apart):
// a (2, 3) torus knot tube covered in flat discs with a checker of coloured stripes, ...
inline constexpr size_t kDemoKnotGaussians = 640 * 48;
// ... a ground disc of flat grey-checker discs under it (z = -0.5, radius 1.25), ...
inline constexpr size_t kDemoGroundGaussians = 7837;
// ... and floaters: large, faint blobs around the knot, the kind of clutter pruning should remove.
inline constexpr size_t kDemoFloaters = 48;
// Every Gaussian centre lies within this distance of the origin; the knot itself within 0.9.
inline constexpr double kDemoSceneRadius = 1.5;

// The demo scene, SH degree 3 (small view-dependent terms, so SH evaluation is exercised).
// The same seed gives bit-identical arrays with any compiler, standard library and platform:
// it uses std::mt19937's raw output (which the standard fixes) with its own distributions, and its
// own sine, cosine and logarithm, because std:: distributions and libm differ between platforms.
GaussianCloud make_demo_scene(uint32_t seed = 1);

// `count` cameras evenly spaced in azimuth (starting on the +x axis, counter-clockwise seen from
// above) at `radius` from the origin and `elevation_deg` above the xy plane, each looking at the
// origin with +z up, fx = fy for a 50 degree horizontal field of view. Named "orbit_000", ...
// A radius of 4 frames the whole demo scene. Throws std::invalid_argument for a count or size
// below 1, a non-positive radius, or an elevation not strictly between -90 and 90 degrees.
std::vector<Camera> make_orbit_cameras(int count, int width, int height, double radius,
                                       double elevation_deg);

}  // namespace vksplat
