#pragma once
// Fingerprints that tell one run's inputs from another's, for the record a checkpoint keeps of
// the run it belongs to: 64-bit FNV-1a over the values, as 16 hex digits. Not cryptographic: they
// guard against mistakes (another scene's checkpoint), not against forgery.
#include <array>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::jobs {

// Of the Gaussians' values and SH degree, so that the same scene in another file (or format that
// keeps every value) has the same fingerprint.
std::string fingerprint(const GaussianCloud& cloud);
// Of each camera's name, size, intrinsics and pose, in order.
std::string fingerprint(const std::vector<Camera>& cameras);

// Recipe values as a checkpoint's owner records them: "0,3,5", "1,1,1".
std::string list_text(const std::vector<size_t>& values);
std::string colour_text(const std::array<float, 3>& colour);

}  // namespace vksplat::jobs
