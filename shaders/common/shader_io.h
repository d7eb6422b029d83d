// The prelude of every header that glslang and the C++ compiler both compile (shaders/README.md):
// GLSL's scalar and vector names, buffer references and constants written once for both sides.
// - In GLSL, BUFFER_REFERENCE(Name, Element, align) declares a buffer_reference type Name with an
//   array `v` of Element; in C++ Name is gpu::DeviceAddress<Element>, a typed 8-byte address.
// - SHADER_CONST(type, NAME, value) is a GLSL `const` and a C++ `inline constexpr`.
// - Declarations of a header sit in namespace vksplat::shader::<module> in C++
//   (SHADER_NAMESPACE_BEGIN(module) ... SHADER_NAMESPACE_END); GLSL has no namespaces.
// A push struct is laid out identically by both (std430 push constants in GLSL, the natural
// layout in C++) as long as its vectors are vec2/vec4 types of this file (never vec3, whose
// std430 size and alignment differ) and its members use only the types here; every generated
// kernel header also checks its push struct's size and member offsets against glslang's
// reflection (cmake/EmbedKernel.cmake).
#ifndef VKSPLAT_SHADER_IO_H
#define VKSPLAT_SHADER_IO_H

#ifdef __cplusplus

#include <cstddef>
#include <cstdint>

#include "gpu/device_address.hpp"

namespace vksplat::shader {

using uint = std::uint32_t;

// A GLSL vector as std430 lays it out: N elements, aligned to their size (vec2: 8, vec4: 16).
template <class T, std::size_t N>
struct alignas(N * sizeof(T)) Vector {
    T v[N];
    constexpr T& operator[](std::size_t i) { return v[i]; }
    constexpr const T& operator[](std::size_t i) const { return v[i]; }
};
using vec2 = Vector<float, 2>;
using vec4 = Vector<float, 4>;
using uvec2 = Vector<uint, 2>;
using uvec4 = Vector<uint, 4>;

}  // namespace vksplat::shader

#define SHADER_NAMESPACE_BEGIN(module) namespace vksplat::shader::module {
#define SHADER_NAMESPACE_END }
#define SHADER_CONST(type, name, value) inline constexpr type name = value;
#define BUFFER_REFERENCE(Name, Element, align) using Name = ::vksplat::gpu::DeviceAddress<Element>;
// An address the shader tests for 0 before it uses it: uvec2 in GLSL (GL_EXT_buffer_reference_uvec2).
#define OPTIONAL_ADDRESS(Name) Name

#else  // GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require

#define SHADER_NAMESPACE_BEGIN(module)
#define SHADER_NAMESPACE_END
#define SHADER_CONST(type, name, value) const type name = value;
#define BUFFER_REFERENCE(Name, Element, align) \
    layout(buffer_reference, std430, buffer_reference_align = align) buffer Name { Element v[]; };
#define OPTIONAL_ADDRESS(Name) uvec2

#endif

#endif
