#pragma once
// Buffer: one VkBuffer with its own memory (RAII). Device buffers carry a device address, which
// the shaders use through GL_EXT_buffer_reference, so a pass needs no descriptor sets.
#include <volk.h>

#include <cstddef>
#include <string>

#include "vksplat/gpu/context.hpp"

namespace vksplat::gpu {

enum class MemoryKind {
    device,    // device-local storage, addressable from shaders
    upload,    // host-visible staging for host -> device copies
    readback,  // host-visible (cached where possible) for device -> host copies
};

class Buffer {
public:
    Buffer() = default;
    // Throws GpuError naming `name` and the size when memory runs out.
    Buffer(const Context& context, VkDeviceSize size, MemoryKind kind, std::string name);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkDeviceAddress address() const { return address_; }
    // Host pointer for upload/readback buffers (persistently mapped); nullptr for device buffers.
    void* mapped() const { return mapped_; }
    const std::string& name() const { return name_; }
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

private:
    void release();

    const Context* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceSize counted_ = 0;  // device memory this buffer adds to its context's held bytes
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;
    std::string name_;
};

// Frees `buffer`, then makes a new one of `bytes` in its place, so that growing never holds the old
// and the new at once (a pass's memory stays within what its sizes promise). Contents are not kept.
void replace(Buffer& buffer, const Context& context, VkDeviceSize bytes, MemoryKind kind, const char* name);

// Replaces `buffer` by one of at least `bytes` where it is smaller (or empty); the contents are not
// kept. For scratch that grows with its work and is reused, so that steady work allocates nothing.
void reserve(Buffer& buffer, const Context& context, VkDeviceSize bytes, MemoryKind kind, const char* name);

}  // namespace vksplat::gpu
