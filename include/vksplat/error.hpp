#pragma once
// Errors a user can act on. Every message names the thing at fault (a file, a camera, a device)
// and what is wrong with it.
#include <stdexcept>
#include <string>

namespace vksplat {

// Bad input: a malformed or truncated file, an invalid camera, an image of the wrong size.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
    // "<where>: <problem>", e.g. "scene.ply: vertex 12: truncated (file ends at byte 3000)".
    InputError(const std::string& where, const std::string& problem)
        : std::runtime_error(where + ": " + problem) {}
};

// The GPU could not do what was asked: no device, out of device memory, a Vulkan failure.
class GpuError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace vksplat
