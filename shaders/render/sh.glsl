// Spherical-harmonics colour, exactly as the reference's computeColorFromSH (same constants,
// same signs, same band order). Coefficients are [coefficient][rgb] per Gaussian, stored either as
// floats or, to halve the largest part of the scene, as IEEE halves packed two per uint.
#ifndef VKSPLAT_SH_GLSL
#define VKSPLAT_SH_GLSL

#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_EXT_control_flow_attributes : require

#include "shaders/common/buffers.h"

const float SH_C0 = 0.28209479177387814;
const float SH_C1 = 0.4886025119029199;
const float SH_C2[5] = float[](1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                               -1.0925484305920792, 0.5462742152960396);
const float SH_C3[7] = float[](-0.5900435899266435, 2.890611442640554, -0.4570457994644658,
                               0.3731763325901154, -0.4570457994644658, 1.445305721320277,
                               -0.5900435899266435);

const uint SH_MAX_VALUES = 48;  // one Gaussian up to degree 3: 16 coefficients x rgb

float packed_half(Uints words, uint i) {
    const vec2 pair = unpackHalf2x16(words.v[i >> 1u]);
    return (i & 1u) == 0u ? pair.x : pair.y;
}

// Where a Gaussian's values are and how to read them. Where every Gaussian's values start on a
// 16-byte boundary (degree 3, or degree 1 as floats, in an aligned buffer) they are read 16 bytes
// at a time: a Gaussian's 192 bytes of float SH read as 48 scalar loads, each touching 32 cache
// lines across a subgroup, made preprocess wait on the cache's line lookups rather than on memory
// (lego tiled 5x5, 6.1 M Gaussians). A trainable scene's SH block is aligned only when its
// Gaussian count is a multiple of 4; elsewhere each coefficient is read where it is used.
struct ShSource {
    Floats sh;
    bool half_storage;
    bool quads;  // 16-byte loads
    uint base;   // index of the Gaussian's first value (float or half)
};

ShSource sh_source(Floats sh, bool half_storage, uint base) {
    const uint bytes_per_value = half_storage ? 2u : 4u;
    const bool quads = (uvec2(sh).x & 15u) == 0u && (base * bytes_per_value) % 16u == 0u;
    return ShSource(sh, half_storage, quads, base);
}

// The first `count` values, 16 bytes at a time (s.quads).
void load_sh_quads(ShSource s, uint count, out float values[SH_MAX_VALUES]) {
    [[unroll]] for (uint n = 0u; n < SH_MAX_VALUES; ++n) values[n] = 0.0;
    if (s.half_storage) {
        UVec4s quads = UVec4s(s.sh);
        [[unroll]] for (uint q = 0u; q < SH_MAX_VALUES / 8u; ++q) {
            if (8u * q >= count) break;
            const uvec4 w = quads.v[s.base / 8u + q];
            const vec2 p0 = unpackHalf2x16(w.x), p1 = unpackHalf2x16(w.y), p2 = unpackHalf2x16(w.z),
                       p3 = unpackHalf2x16(w.w);
            values[8u * q] = p0.x, values[8u * q + 1u] = p0.y, values[8u * q + 2u] = p1.x;
            values[8u * q + 3u] = p1.y, values[8u * q + 4u] = p2.x, values[8u * q + 5u] = p2.y;
            values[8u * q + 6u] = p3.x, values[8u * q + 7u] = p3.y;
        }
    } else {
        Vec4s quads = Vec4s(s.sh);
        [[unroll]] for (uint q = 0u; q < SH_MAX_VALUES / 4u; ++q) {
            if (4u * q >= count) break;
            const vec4 v = quads.v[s.base / 4u + q];
            values[4u * q] = v.x, values[4u * q + 1u] = v.y, values[4u * q + 2u] = v.z, values[4u * q + 3u] = v.w;
        }
    }
}

// Coefficient k's rgb, read where it is needed (not s.quads).
vec3 sh_coefficient(ShSource s, uint k) {
    const uint i = s.base + 3u * k;
    if (s.half_storage) {
        Uints words = Uints(s.sh);
        return vec3(packed_half(words, i), packed_half(words, i + 1u), packed_half(words, i + 2u));
    }
    return vec3(s.sh.v[i], s.sh.v[i + 1u], s.sh.v[i + 2u]);
}

// Basis function k (0 to 15) at the unit direction (x, y, z), up to the sign the sum gives it (1 and
// 3 are subtracted), over the products xx ... xz of the enclosing scope: one formula for the colour
// and its backward (sh_basis_function). Bare tokens, not parenthesised, so that the colour's sum
// expands to the reference's expression as written, operation for operation.
#define SH_BASIS_0 SH_C0
#define SH_BASIS_1 SH_C1 * y
#define SH_BASIS_2 SH_C1 * z
#define SH_BASIS_3 SH_C1 * x
#define SH_BASIS_4 SH_C2[0] * xy
#define SH_BASIS_5 SH_C2[1] * yz
#define SH_BASIS_6 SH_C2[2] * (2.0 * zz - xx - yy)
#define SH_BASIS_7 SH_C2[3] * xz
#define SH_BASIS_8 SH_C2[4] * (xx - yy)
#define SH_BASIS_9 SH_C3[0] * y * (3.0 * xx - yy)
#define SH_BASIS_10 SH_C3[1] * xy * z
#define SH_BASIS_11 SH_C3[2] * y * (4.0 * zz - xx - yy)
#define SH_BASIS_12 SH_C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy)
#define SH_BASIS_13 SH_C3[4] * x * (4.0 * zz - xx - yy)
#define SH_BASIS_14 SH_C3[5] * z * (xx - yy)
#define SH_BASIS_15 SH_C3[6] * x * (xx - 3.0 * yy)

// The reference's sum over bands, returned from the enclosing function, with COEFF(k) giving
// coefficient k's rgb: one formula for both ways of reading the values.
#define SH_RETURN_SUM(COEFF)                                                                            \
    {                                                                                                   \
        vec3 result = SH_BASIS_0 * COEFF(0);                                                            \
        if (degree > 0u) {                                                                              \
            const float x = dir.x, y = dir.y, z = dir.z;                                                \
            result = result - SH_BASIS_1 * COEFF(1) + SH_BASIS_2 * COEFF(2) - SH_BASIS_3 * COEFF(3);    \
            if (degree > 1u) {                                                                          \
                const float xx = x * x, yy = y * y, zz = z * z;                                         \
                const float xy = x * y, yz = y * z, xz = x * z;                                         \
                result = result + SH_BASIS_4 * COEFF(4) + SH_BASIS_5 * COEFF(5) + SH_BASIS_6 * COEFF(6) + \
                         SH_BASIS_7 * COEFF(7) + SH_BASIS_8 * COEFF(8);                                 \
                if (degree > 2u) {                                                                      \
                    result = result + SH_BASIS_9 * COEFF(9) + SH_BASIS_10 * COEFF(10) +                 \
                             SH_BASIS_11 * COEFF(11) + SH_BASIS_12 * COEFF(12) +                        \
                             SH_BASIS_13 * COEFF(13) + SH_BASIS_14 * COEFF(14) + SH_BASIS_15 * COEFF(15); \
                }                                                                                       \
            }                                                                                           \
        }                                                                                               \
        return result;                                                                                  \
    }

// Basis function k (0 to 15) at the unit direction `dir`, signed as the colour's sum uses it: the
// derivative of SH(dir) with respect to coefficient k.
float sh_basis_function(uint k, vec3 dir) {
    const float x = dir.x, y = dir.y, z = dir.z;
    const float xx = x * x, yy = y * y, zz = z * z;
    const float xy = x * y, yz = y * z, xz = x * z;
    switch (k) {
        case 0u: return SH_BASIS_0;
        case 1u: return -(SH_BASIS_1);
        case 2u: return SH_BASIS_2;
        case 3u: return -(SH_BASIS_3);
        case 4u: return SH_BASIS_4;
        case 5u: return SH_BASIS_5;
        case 6u: return SH_BASIS_6;
        case 7u: return SH_BASIS_7;
        case 8u: return SH_BASIS_8;
        case 9u: return SH_BASIS_9;
        case 10u: return SH_BASIS_10;
        case 11u: return SH_BASIS_11;
        case 12u: return SH_BASIS_12;
        case 13u: return SH_BASIS_13;
        case 14u: return SH_BASIS_14;
        default: return SH_BASIS_15;
    }
}

// SH(dir) without the 0.5 offset, each coefficient read where it is used. dir: unit vector from
// the camera centre to the Gaussian. For kernels that must not hold the 48 values at once: the
// registers of eval_sh's 16-byte path are reserved for the whole kernel even where it never runs
// (H100, bonsai re-fit: preprocess_backward 0.405 -> 0.454 ms).
vec3 eval_sh_in_place(ShSource s, uint degree, vec3 dir) {
#define SH_READ(k) sh_coefficient(s, k)
    SH_RETURN_SUM(SH_READ)
#undef SH_READ
}

// base: index of the Gaussian's first value (float or half). dir: unit vector from the camera
// centre to the Gaussian. Returns SH(dir) without the 0.5 offset.
vec3 eval_sh(Floats sh, bool half_storage, uint base, uint degree, vec3 dir) {
    ShSource s = sh_source(sh, half_storage, base);
    if (s.quads) {
        float v[SH_MAX_VALUES];
        load_sh_quads(s, 3u * (degree + 1u) * (degree + 1u), v);
#define SH_LOADED(k) vec3(v[3 * (k)], v[3 * (k) + 1], v[3 * (k) + 2])
        SH_RETURN_SUM(SH_LOADED)
#undef SH_LOADED
    }
    return eval_sh_in_place(s, degree, dir);
}
#undef SH_RETURN_SUM
#undef SH_BASIS_0
#undef SH_BASIS_1
#undef SH_BASIS_2
#undef SH_BASIS_3
#undef SH_BASIS_4
#undef SH_BASIS_5
#undef SH_BASIS_6
#undef SH_BASIS_7
#undef SH_BASIS_8
#undef SH_BASIS_9
#undef SH_BASIS_10
#undef SH_BASIS_11
#undef SH_BASIS_12
#undef SH_BASIS_13
#undef SH_BASIS_14
#undef SH_BASIS_15

#endif
