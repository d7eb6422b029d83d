// Typed views of device memory that every module's passes share. Every pass receives its buffers
// as device addresses in its push constants (GL_EXT_buffer_reference), so a pass is one shader, one
// layout header and one small host function, with no descriptor sets to keep in step.
#ifndef VKSPLAT_BUFFERS_H
#define VKSPLAT_BUFFERS_H

#include "shaders/common/shader_io.h"

#ifdef __cplusplus
namespace vksplat::shader {
#endif

BUFFER_REFERENCE(Uints, uint, 4)
BUFFER_REFERENCE(Floats, float, 4)
BUFFER_REFERENCE(Vec2s, vec2, 8)
BUFFER_REFERENCE(UVec2s, uvec2, 8)
BUFFER_REFERENCE(Vec4s, vec4, 16)
BUFFER_REFERENCE(UVec4s, uvec4, 16)

// VkDispatchIndirectCommand as the GPU writes it for dispatch_indirect().
struct DispatchArgs {
    uint x;
    uint y;
    uint z;
};
BUFFER_REFERENCE(DispatchArgsBuffer, DispatchArgs, 4)

// Largest group count we put in one dimension: Vulkan only promises 65535. Kernels whose element
// count can exceed 65535 groups' worth walk their elements in a grid-stride loop.
SHADER_CONST(uint, MAX_GROUPS_X, 65535)

#ifdef __cplusplus
}  // namespace vksplat::shader
#else
uint groups_for(uint count, uint per_group) {
    return min((count + per_group - 1) / per_group, MAX_GROUPS_X);
}
#endif

#endif
