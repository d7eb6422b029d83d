// Per-frame data shared by the render passes (and training's, which record them): the camera
// (uploaded with vkCmdUpdateBuffer at the start of each frame, render::make_camera_params in
// src/render/frame_layout.cpp) and the frame's counters (written by the GPU, never by the host
// mid-frame; the host reads them after the submission).
#ifndef VKSPLAT_RENDER_FRAME_H
#define VKSPLAT_RENDER_FRAME_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(render)

struct CameraParams {
    vec4 view_row0;        // world->camera: rotation row 0 (xyz) and translation x (w)
    vec4 view_row1;
    vec4 view_row2;
    vec4 position;         // camera centre in world space (xyz)
    vec4 focal_principal;  // fx, fy, cx - 0.5, cy - 0.5 (pixel centres at integer coordinates)
    vec4 jacobian_limits;  // tan limits of the EWA clamp: -x, +x, -y, +y
    uvec4 size;            // width, height, tiles_x, tiles_y
    vec4 background;       // rgb
    uint gaussian_count;
    uint sh_degree;        // degree evaluated (the cap and the scene's degree, whichever is lower)
    uint sh_stride;        // SH coefficients stored per Gaussian (scene degree)
    uint entry_capacity;   // tile entries the frame's buffers hold
    uint sh_half;          // 1: SH stored as packed halves (SceneStorage::half_sh)
    uint write_projection;  // 1: preprocess writes means_depth, which only statistics and training read
    uint padding[2];
};

#ifdef __cplusplus
BUFFER_REFERENCE(CameraBuffer, CameraParams, 16)
// Slots of the frame counters buffer (uints): C++ names them kCounter..., GLSL COUNTER_....
#define FRAME_COUNTER(glsl_name, cpp_name, value) inline constexpr uint cpp_name = value;
#else
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer CameraBuffer { CameraParams c; };
#define FRAME_COUNTER(glsl_name, cpp_name, value) const uint glsl_name = value;
#endif

FRAME_COUNTER(COUNTER_GAUSSIANS, kCounterGaussians, 0)            // filled by the host's fill command
FRAME_COUNTER(COUNTER_VISIBLE, kCounterVisible, 1)                // splats that survived culling
FRAME_COUNTER(COUNTER_ENTRIES_NEEDED, kCounterEntriesNeeded, 2)   // tile entries the frame needs
FRAME_COUNTER(COUNTER_ENTRIES, kCounterEntries, 3)                // tile entries written (needed, clamped to capacity)
FRAME_COUNTER(COUNTER_VISIBLE_ARGS, kCounterVisibleArgs, 4)       // DispatchArgs over visible splats (3 uints)
FRAME_COUNTER(COUNTER_ENTRY_ARGS, kCounterEntryArgs, 7)           // DispatchArgs over tile entries (3 uints)
FRAME_COUNTER(COUNTER_COUNT, kCounterCount, 10)
#undef FRAME_COUNTER

SHADER_NAMESPACE_END

#endif
