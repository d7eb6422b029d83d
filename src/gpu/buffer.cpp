#include "gpu/buffer.hpp"

#include <utility>

#include "gpu/context_impl.hpp"
#include "gpu/vk_check.hpp"

namespace vksplat::gpu {
namespace {

uint32_t find_memory_type(const VkPhysicalDeviceMemoryProperties& memory, uint32_t allowed,
                          VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
    int fallback = -1;
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if (!(allowed & (1u << i))) continue;
        const auto flags = memory.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback < 0) fallback = static_cast<int>(i);
    }
    if (fallback < 0) throw GpuError("no suitable Vulkan memory type");
    return static_cast<uint32_t>(fallback);
}

}  // namespace

Buffer::Buffer(const Context& context, VkDeviceSize size, MemoryKind kind, std::string name)
    : context_(&context), size_(size), name_(std::move(name)) {
    const auto& d = context.impl();
    // Zero-sized buffers are invalid in Vulkan; a tiny one keeps empty scenes on the normal path.
    const VkDeviceSize alloc_size = size > 0 ? size : 16;

    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = alloc_size;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (kind == MemoryKind::device)
        info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                      VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    try {
        VKSPLAT_VK(d.vk.vkCreateBuffer(d.device, &info, nullptr, &buffer_));

        VkMemoryRequirements requirements{};
        d.vk.vkGetBufferMemoryRequirements(d.device, buffer_, &requirements);
        VkMemoryPropertyFlags required = 0, preferred = 0;
        switch (kind) {
            case MemoryKind::device: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
            case MemoryKind::upload:
                required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
                break;
            case MemoryKind::readback:
                required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
                preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
                break;
        }
        VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.pNext = kind == MemoryKind::device ? &flags : nullptr;
        alloc.allocationSize = requirements.size;
        alloc.memoryTypeIndex = find_memory_type(d.memory, requirements.memoryTypeBits, required, preferred);
        const VkResult result = d.vk.vkAllocateMemory(d.device, &alloc, nullptr, &memory_);
        if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
            throw GpuError(out_of_memory_message(result, name_, alloc_size, d.info));
        check(result, "vkAllocateMemory");
        if (kind == MemoryKind::device) {
            counted_ = requirements.size;
            d.device_bytes_allocated(counted_);
        }
        VKSPLAT_VK(d.vk.vkBindBufferMemory(d.device, buffer_, memory_, 0));
        if (kind != MemoryKind::device)
            VKSPLAT_VK(d.vk.vkMapMemory(d.device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
        else {
            VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
            address.buffer = buffer_;
            address_ = d.vk.vkGetBufferDeviceAddress(d.device, &address);
        }
    } catch (...) {
        release();
        throw;
    }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        context_ = std::exchange(other.context_, nullptr);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        counted_ = std::exchange(other.counted_, 0);
        address_ = std::exchange(other.address_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
        name_ = std::move(other.name_);
    }
    return *this;
}

void Buffer::release() {
    if (!context_) return;
    const auto& d = context_->impl();
    if (buffer_) d.vk.vkDestroyBuffer(d.device, buffer_, nullptr);
    if (memory_) d.vk.vkFreeMemory(d.device, memory_, nullptr);  // unmaps implicitly
    d.device_bytes_freed(std::exchange(counted_, 0));
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    address_ = 0;
}

void replace(Buffer& buffer, const Context& context, VkDeviceSize bytes, MemoryKind kind, const char* name) {
    buffer = Buffer();
    buffer = Buffer(context, bytes, kind, name);
}

void reserve(Buffer& buffer, const Context& context, VkDeviceSize bytes, MemoryKind kind, const char* name) {
    if (buffer && buffer.size() >= bytes) return;
    replace(buffer, context, bytes, kind, name);
}

}  // namespace vksplat::gpu
