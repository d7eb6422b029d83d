#pragma once
// DeviceAddress<T>: the C++ side of a GLSL buffer reference (GL_EXT_buffer_reference) to an array
// of T. Pass layout headers (shaders/<module>/*.h, see shaders/README.md) declare their push
// members with these types, so that the push struct that glslang and the C++ compiler both compile
// says what each address points at: an address of one element type does not convert to another.
// A buffer's untyped address (Buffer::address(), plus an offset) converts implicitly, since
// buffers are untyped; designated initialisers then name the member it goes to.
#include <volk.h>

#include <cstdint>

namespace vksplat::gpu {

template <class T>
struct DeviceAddress {
    using Element = T;
    VkDeviceAddress value = 0;  // 0: no buffer (for members a shader may skip)

    constexpr DeviceAddress() = default;
    constexpr DeviceAddress(VkDeviceAddress address) : value(address) {}
};

// A GLSL buffer reference is 8 bytes, 8-byte aligned in push constants (std430 and scalar alike).
static_assert(sizeof(DeviceAddress<float>) == 8 && alignof(DeviceAddress<float>) == 8);

}  // namespace vksplat::gpu
