#pragma once
// Shared by the gpu tests: one Context per test binary (creating a device and compiling pipelines
// is the slow part on lavapipe) and helpers to move uint arrays to and from device buffers.
#include "gpu/buffer.hpp"
#include "gpu/command_stream.hpp"
#include "support/gpu_fixture.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace vksplat::test {

// The test binary's one context, checked by the validation layer when it is installed.
inline gpu::Context& shared_context() { return shared_test_context(); }

inline gpu::Buffer device_buffer(const gpu::Context& context, size_t elements, const char* name) {
    return gpu::Buffer(context, elements * sizeof(uint32_t), gpu::MemoryKind::device, name);
}

// Host-visible copy of `data`, kept alive until the stream has run.
inline gpu::Buffer staging(const gpu::Context& context, const std::vector<uint32_t>& data) {
    gpu::Buffer buffer(context, data.size() * sizeof(uint32_t), gpu::MemoryKind::upload, "test upload");
    if (!data.empty()) std::memcpy(buffer.mapped(), data.data(), data.size() * sizeof(uint32_t));
    return buffer;
}

inline std::vector<uint32_t> read_back(const gpu::Context& context, const gpu::Buffer& buffer, size_t elements) {
    gpu::Buffer host(context, elements * sizeof(uint32_t), gpu::MemoryKind::readback, "test readback");
    gpu::CommandStream stream(context);
    stream.begin();
    stream.copy(buffer, host, elements * sizeof(uint32_t));
    stream.submit_and_wait();
    std::vector<uint32_t> result(elements);
    if (elements) std::memcpy(result.data(), host.mapped(), elements * sizeof(uint32_t));
    return result;
}

// A device buffer holding `data`.
inline gpu::Buffer upload(const gpu::Context& context, const std::vector<uint32_t>& data, const char* name) {
    gpu::Buffer buffer = device_buffer(context, data.size(), name);
    gpu::Buffer host = staging(context, data);
    gpu::CommandStream stream(context);
    stream.begin();
    stream.copy(host, buffer, data.size() * sizeof(uint32_t));
    stream.submit_and_wait();
    return buffer;
}

// Index of the first difference between two arrays, or -1; keeps failure messages short.
inline long first_difference(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
    if (a.size() != b.size()) return 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return static_cast<long>(i);
    return -1;
}

}  // namespace vksplat::test
