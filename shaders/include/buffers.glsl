// Typed views of device memory. Every pass receives its buffers as device addresses in its push
// constants (GL_EXT_buffer_reference), so a pass is one shader plus one small host function with
// no descriptor sets to keep in step.
#ifndef VKSPLAT_BUFFERS_GLSL
#define VKSPLAT_BUFFERS_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require

layout(buffer_reference, std430, buffer_reference_align = 4) buffer Uints { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer Vec2s { vec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer UVec2s { uvec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4s { uvec4 v[]; };

// VkDispatchIndirectCommand as the GPU writes it for dispatch_indirect().
struct DispatchArgs {
    uint x;
    uint y;
    uint z;
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer DispatchArgsBuffer { DispatchArgs v[]; };

// Largest group count we put in one dimension: Vulkan only promises 65535. Kernels whose element
// count can exceed 65535 groups' worth walk their elements in a grid-stride loop.
const uint MAX_GROUPS_X = 65535;

uint groups_for(uint count, uint per_group) {
    return min((count + per_group - 1) / per_group, MAX_GROUPS_X);
}

#endif
