// Per-frame data shared by the render passes: the camera (uploaded with vkCmdUpdateBuffer at
// the start of each frame) and the frame's counters (written by the GPU, never by the host
// mid-frame). src/render/frame_layout.hpp is the C++ twin of these layouts.
#ifndef VKSPLAT_FRAME_GLSL
#define VKSPLAT_FRAME_GLSL

#include "buffers.glsl"

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
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer CameraBuffer { CameraParams c; };

// Indices into the frame counters buffer (uints).
const uint COUNTER_GAUSSIANS = 0;        // filled by the host's fill command
const uint COUNTER_VISIBLE = 1;          // splats that survived culling
const uint COUNTER_ENTRIES_NEEDED = 2;   // tile entries the frame needs
const uint COUNTER_ENTRIES = 3;          // tile entries written (needed, clamped to capacity)
const uint COUNTER_VISIBLE_ARGS = 4;     // DispatchArgs over visible splats (3 uints)
const uint COUNTER_ENTRY_ARGS = 7;       // DispatchArgs over tile entries (3 uints)
const uint COUNTER_COUNT = 10;

#endif
