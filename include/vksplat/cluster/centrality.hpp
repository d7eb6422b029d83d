#pragma once
// Centrality: how much the views look at a Gaussian. In a capture that circles a subject every
// camera points at it, so a subject Gaussian projects near the middle of nearly every picture; a
// wall, floor or piece of furniture is in the middle of the few pictures taken towards it, near
// the edge of some more, and behind the camera in the rest. Per view, a Gaussian in front of the
// camera scores 1 - rho^2 at its projected centre, rho the distance from the image's centre
// relative to the half-width and half-height (rho = 1 on the ellipse touching the image's
// sides), and 0 beyond rho = 1 or behind the near plane; its centrality is the mean over the views.
// Purely geometric: it needs no segmentation and no occlusion test, and finds the subject without
// hand-picked views.
#include <span>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::cluster {

// positions: 3 floats per Gaussian. One value in [0, 1] per Gaussian; all 0 without views.
std::vector<float> view_centrality(std::span<const float> positions, const std::vector<Camera>& cameras);


}  // namespace vksplat::cluster
