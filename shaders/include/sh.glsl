// Spherical-harmonics colour, exactly as the reference's computeColorFromSH (same constants,
// same signs, same band order). Coefficients are [coefficient][rgb] per Gaussian, stored either as
// floats or, to halve the largest part of the scene, as IEEE halves packed two per uint.
#ifndef VKSPLAT_SH_GLSL
#define VKSPLAT_SH_GLSL

#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_EXT_control_flow_attributes : require

#include "buffers.glsl"

const float SH_C0 = 0.28209479177387814;
const float SH_C1 = 0.4886025119029199;
const float SH_C2[5] = float[](1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                               -1.0925484305920792, 0.5462742152960396);
const float SH_C3[7] = float[](-0.5900435899266435, 2.890611442640554, -0.4570457994644658,
                               0.3731763325901154, -0.4570457994644658, 1.445305721320277,
                               -0.5900435899266435);

// Values of one Gaussian up to degree 3: 16 coefficients x rgb.
const uint SH_MAX_VALUES = 48;

float packed_half(Uints words, uint i) {
    const vec2 pair = unpackHalf2x16(words.v[i >> 1u]);
    return (i & 1u) == 0u ? pair.x : pair.y;
}

// The first `count` values of a Gaussian whose first value is number `base` of the buffer. Where
// every Gaussian's values start on a 16-byte boundary (degree 3, or degree 1 as floats, in an
// aligned buffer), they are read 16 bytes at a time: a Gaussian's 192 bytes of float SH read as
// 48 scalar loads, each touching 32 cache lines across a subgroup, made preprocess wait on the
// cache's line lookups rather than on memory (lego tiled 5x5: 6.1 M Gaussians).
void load_sh_values(Floats sh, bool half_storage, uint base, uint count, out float values[SH_MAX_VALUES]) {
    const uint bytes_per_value = half_storage ? 2u : 4u;
    const bool aligned = (uvec2(sh).x & 15u) == 0u && (base * bytes_per_value) % 16u == 0u;
    [[unroll]] for (uint n = 0u; n < SH_MAX_VALUES; ++n) values[n] = 0.0;
    if (aligned && half_storage) {
        UVec4s quads = UVec4s(sh);
        [[unroll]] for (uint q = 0u; q < SH_MAX_VALUES / 8u; ++q) {
            if (8u * q >= count) break;
            const uvec4 w = quads.v[base / 8u + q];
            const vec2 p0 = unpackHalf2x16(w.x), p1 = unpackHalf2x16(w.y), p2 = unpackHalf2x16(w.z),
                       p3 = unpackHalf2x16(w.w);
            values[8u * q] = p0.x, values[8u * q + 1u] = p0.y, values[8u * q + 2u] = p1.x;
            values[8u * q + 3u] = p1.y, values[8u * q + 4u] = p2.x, values[8u * q + 5u] = p2.y;
            values[8u * q + 6u] = p3.x, values[8u * q + 7u] = p3.y;
        }
    } else if (aligned) {
        Vec4s quads = Vec4s(sh);
        [[unroll]] for (uint q = 0u; q < SH_MAX_VALUES / 4u; ++q) {
            if (4u * q >= count) break;
            const vec4 v = quads.v[base / 4u + q];
            values[4u * q] = v.x, values[4u * q + 1u] = v.y, values[4u * q + 2u] = v.z, values[4u * q + 3u] = v.w;
        }
    } else {
        [[unroll]] for (uint n = 0u; n < SH_MAX_VALUES; ++n) {
            if (n >= count) break;
            values[n] = half_storage ? packed_half(Uints(sh), base + n) : sh.v[base + n];
        }
    }
}

// base: index of the Gaussian's first value (float or half). dir: unit vector from the camera
// centre to the Gaussian. Returns SH(dir) without the 0.5 offset.
vec3 eval_sh(Floats sh, bool half_storage, uint base, uint degree, vec3 dir) {
    float v[SH_MAX_VALUES];
    load_sh_values(sh, half_storage, base, 3u * (degree + 1u) * (degree + 1u), v);
#define SH_K(k) vec3(v[3 * (k)], v[3 * (k) + 1], v[3 * (k) + 2])
    vec3 result = SH_C0 * SH_K(0);
    if (degree > 0u) {
        const float x = dir.x, y = dir.y, z = dir.z;
        result = result - SH_C1 * y * SH_K(1) + SH_C1 * z * SH_K(2) - SH_C1 * x * SH_K(3);
        if (degree > 1u) {
            const float xx = x * x, yy = y * y, zz = z * z;
            const float xy = x * y, yz = y * z, xz = x * z;
            result = result + SH_C2[0] * xy * SH_K(4) + SH_C2[1] * yz * SH_K(5) +
                     SH_C2[2] * (2.0 * zz - xx - yy) * SH_K(6) + SH_C2[3] * xz * SH_K(7) +
                     SH_C2[4] * (xx - yy) * SH_K(8);
            if (degree > 2u) {
                result = result + SH_C3[0] * y * (3.0 * xx - yy) * SH_K(9) + SH_C3[1] * xy * z * SH_K(10) +
                         SH_C3[2] * y * (4.0 * zz - xx - yy) * SH_K(11) +
                         SH_C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * SH_K(12) +
                         SH_C3[4] * x * (4.0 * zz - xx - yy) * SH_K(13) + SH_C3[5] * z * (xx - yy) * SH_K(14) +
                         SH_C3[6] * x * (xx - 3.0 * yy) * SH_K(15);
            }
        }
    }
#undef SH_K
    return result;
}

#endif
