#pragma once
// One-off host <-> device copies through a staging buffer (scene upload, test data). Per-frame
// traffic does not go through here: it is recorded into the frame's own command stream.
#include <string>
#include <vector>

#include "gpu/buffer.hpp"

namespace vksplat::gpu {

// A device buffer holding a copy of `bytes` bytes of `data`.
Buffer upload_buffer(const Context& context, const void* data, size_t bytes, std::string name);

template <class T>
Buffer upload_buffer(const Context& context, const std::vector<T>& data, std::string name) {
    return upload_buffer(context, data.data(), data.size() * sizeof(T), std::move(name));
}

// Copies `bytes` bytes from the start of a device buffer to host memory.
void read_buffer(const Context& context, const Buffer& buffer, void* out, size_t bytes);

template <class T>
std::vector<T> read_buffer(const Context& context, const Buffer& buffer, size_t count) {
    std::vector<T> out(count);
    read_buffer(context, buffer, out.data(), count * sizeof(T));
    return out;
}

}  // namespace vksplat::gpu
