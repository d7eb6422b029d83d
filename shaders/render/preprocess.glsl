#ifndef PREPROCESS_HOOKS
#error define gaussian_position_opacity, gaussian_covariance and PREPROCESS_HOOKS first
#endif
// Preprocess: one thread per Gaussian. Culls by the near plane, projects the 3D covariance to
// 2D with the EWA Jacobian (clamped like the reference), adds the low-pass filter, inverts it to
// the conic, bounds it by a 3-sigma radius and a tile rectangle, and evaluates the SH colour.
// Mirrors preprocessCUDA of the reference rasterizer; constants come from vksplat/constants.hpp.
//
// It also writes every Gaussian's depth-sort key: the view depth's bits for a drawn splat, and
// NOT_DRAWN, which sorts after all of them, for the rest. The depth sort then takes all Gaussians
// and the drawn ones come out first, in depth order, ties in index order as in the reference;
// compacting the drawn ones first (a scan and a compaction kernel) cost more, in a frame's chain of
// dependent kernels, than sorting the culled keys along (tile_binning.cpp). Where that sort runs
// one sweep, the keys' digits are counted here too, in place of the sort's histogram kernel.
//
// Included by preprocess.comp (the renderer's activated parameters) and
// shaders/train/preprocess_trainable.comp (the trainer's raw ones, activated as they are read),
// after they declare the push constants (PreprocessPush) and how Gaussian i is read:
//   vec4 gaussian_position_opacity(uint i): position and opacity;
//   mat3 gaussian_covariance(uint i): its 3D covariance (asked only in front of the near plane).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_vote : require

#include "shaders/render/tile_binning.h"
#include "vksplat/constants.hpp"
#include "shaders/render/footprint.h"
#include "shaders/render/frame.h"
#include "shaders/render/sh.glsl"
#include "shaders/render/tile_culling.glsl"
#include "shaders/sort/radix_sort.h"

layout(local_size_x = 256) in;
#include "shaders/sort/radix_digit_counts.glsl"
#include "shaders/common/gaussian_shape.glsl"

// Above the bits of every positive depth (and of every NaN but this one).
const uint NOT_DRAWN = 0xffffffffu;

// Not drawn. The radius is zeroed too: per-Gaussian statistics read "radius > 0" as visible in
// the reference's sense (in front of the near plane, non-empty 3-sigma rectangle).
uint cull(uint i, CameraParams cam) {
    pc.tiles_touched.v[i] = 0u;
    if (cam.write_projection != 0u) pc.means_depth.v[i].w = 0.0;
    return NOT_DRAWN;
}

// Visible to the reference, but touching no pixel (tile_culling.glsl): keep the projection for
// the statistics, draw nothing.
uint skip_untouched(uint i) {
    pc.tiles_touched.v[i] = 0u;
    return NOT_DRAWN;
}

// Writes Gaussian i's splat and returns its depth key.
uint preprocess(uint i, CameraParams cam) {
    const vec4 position_opacity = gaussian_position_opacity(i);
    const vec3 p = position_opacity.xyz;
    const vec3 view = vec3(dot(cam.view_row0.xyz, p) + cam.view_row0.w,
                           dot(cam.view_row1.xyz, p) + cam.view_row1.w,
                           dot(cam.view_row2.xyz, p) + cam.view_row2.w);
    if (view.z <= NEAR_PLANE) return cull(i, cam);

    const mat3 sigma = gaussian_covariance(i);

    // EWA: the Jacobian of the perspective projection at the (clamped) view position. Clamping
    // the lateral position keeps splats far outside the view from growing without bound.
    const float fx = cam.focal_principal.x, fy = cam.focal_principal.y;
    const float tx = clamp(view.x / view.z, -cam.jacobian_limits.x, cam.jacobian_limits.y) * view.z;
    const float ty = clamp(view.y / view.z, -cam.jacobian_limits.z, cam.jacobian_limits.w) * view.z;
    const mat3 jacobian = transpose(mat3(vec3(fx / view.z, 0.0, -(fx * tx) / (view.z * view.z)),
                                         vec3(0.0, fy / view.z, -(fy * ty) / (view.z * view.z)),
                                         vec3(0.0)));
    const mat3 world_to_view = transpose(mat3(cam.view_row0.xyz, cam.view_row1.xyz, cam.view_row2.xyz));
    const mat3 t = jacobian * world_to_view;
    const mat3 cov = t * sigma * transpose(t);
    const float a = cov[0][0] + LOW_PASS_FILTER;
    const float b = cov[1][0];
    const float c = cov[1][1] + LOW_PASS_FILTER;

    const float det = a * c - b * b;
    if (det == 0.0) return cull(i, cam);
    const float det_inv = 1.0 / det;
    const vec3 conic = vec3(c * det_inv, -b * det_inv, a * det_inv);
    const float mid = 0.5 * (a + c);
    const float lambda1 = mid + sqrt(max(EIGENVALUE_FLOOR, mid * mid - det));
    const float lambda2 = mid - sqrt(max(EIGENVALUE_FLOOR, mid * mid - det));
    const float radius = ceil(RADIUS_SIGMAS * sqrt(max(lambda1, lambda2)));

    const vec2 mean = vec2(fx * view.x / view.z + cam.focal_principal.z,
                           fy * view.y / view.z + cam.focal_principal.w);
    // getRect: truncation toward zero, clamped to the grid. Clamping before the conversion
    // keeps far-off splats from overflowing int.
    const vec2 grid = vec2(cam.size.zw);
    const vec2 tile = vec2(TILE_WIDTH, TILE_HEIGHT);
    const uvec2 rect_min = uvec2(max(ivec2(clamp((mean - radius) / tile, vec2(-1.0), grid)), ivec2(0)));
    const uvec2 rect_max =
        uvec2(max(ivec2(clamp((mean + radius + tile - 1.0) / tile, vec2(-1.0), grid)), ivec2(0)));
    if (radius <= 0.0 || any(lessThanEqual(rect_max, rect_min))) return cull(i, cam);
    if (cam.write_projection != 0u) pc.means_depth.v[i] = vec4(mean, view.z, radius);
    // Below 1/255 opacity a splat touches no pixel anywhere (alpha <= opacity).
    const float bound = touch_bound(position_opacity.w);
    if (bound < 0.0) return skip_untouched(i);
    uvec2 lo, hi;
    touched_rect(mean, vec3(a, b, c), bound, rect_min, rect_max, lo, hi);
    uint tiles = 0u;
    for (uint y = lo.y; y < hi.y; ++y) {
        const uvec2 span = row_tile_span(mean, conic, bound, y, lo.x, hi.x);
        tiles += span.y - span.x;
    }
    if (tiles == 0u) return skip_untouched(i);

    const vec3 direction = normalize(p - cam.position.xyz);
    const vec3 color = max(eval_sh(pc.sh, cam.sh_half != 0u, i * cam.sh_stride * 3u, cam.sh_degree, direction) + COLOR_OFFSET,
                           vec3(0.0));

    pc.footprints.v[i] = make_footprint(mean, conic, position_opacity.w, lo, hi);
    pc.colors.v[i] = vec4(color, view.z);
    pc.tiles_touched.v[i] = tiles;
    return min(floatBitsToUint(view.z), NOT_DRAWN - 1u);
}

void main() {
    const CameraParams cam = pc.camera.c;
    const bool count_digits = pc.depth_digits.passes != 0u;  // uniform: the barriers below are allowed
    if (count_digits) {
        radix_clear_lookback(pc.depth_digits.lookback, pc.depth_digits.lookback_words);
        radix_clear_digit_counts();
        barrier();
    }
    uint drawn = 0;
    for (uint i = gl_GlobalInvocationID.x; i < cam.gaussian_count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        pc.depth_values.v[i] = i;
        const uint key = preprocess(i, cam);
        pc.depth_keys.v[i] = key;
        if (key != NOT_DRAWN) ++drawn;
        if (count_digits) radix_count_digits(key, pc.depth_digits.digits, pc.depth_digits.passes);
    }
    // One atomic per subgroup: the count does not depend on the order they land in.
    const uint subgroup_drawn = subgroupAdd(drawn);
    if (subgroupElect() && subgroup_drawn != 0u) atomicAdd(pc.counters.v[COUNTER_VISIBLE], subgroup_drawn);
    if (count_digits) radix_add_digit_counts(pc.depth_digits.totals, pc.depth_digits.passes);
}
