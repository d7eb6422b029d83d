// Spherical-harmonics colour, exactly as the reference's computeColorFromSH (same constants,
// same signs, same band order). Coefficients are [coefficient][rgb] per Gaussian, stored either as
// floats or, to halve the largest part of the scene, as IEEE halves packed two per uint.
#ifndef VKSPLAT_SH_GLSL
#define VKSPLAT_SH_GLSL

#include "buffers.glsl"

const float SH_C0 = 0.28209479177387814;
const float SH_C1 = 0.4886025119029199;
const float SH_C2[5] = float[](1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
                               -1.0925484305920792, 0.5462742152960396);
const float SH_C3[7] = float[](-0.5900435899266435, 2.890611442640554, -0.4570457994644658,
                               0.3731763325901154, -0.4570457994644658, 1.445305721320277,
                               -0.5900435899266435);

float packed_half(Uints words, uint i) {
    const vec2 pair = unpackHalf2x16(words.v[i >> 1u]);
    return (i & 1u) == 0u ? pair.x : pair.y;
}

vec3 sh_coefficient(Floats sh, bool half_storage, uint base, uint k) {
    const uint i = base + 3u * k;
    if (half_storage) {
        Uints words = Uints(sh);
        return vec3(packed_half(words, i), packed_half(words, i + 1u), packed_half(words, i + 2u));
    }
    return vec3(sh.v[i], sh.v[i + 1u], sh.v[i + 2u]);
}

// base: index of the Gaussian's first value (float or half). dir: unit vector from the camera centre to the Gaussian. Returns SH(dir) without the 0.5 offset.
vec3 eval_sh(Floats sh, bool half_storage, uint base, uint degree, vec3 dir) {
    vec3 result = SH_C0 * sh_coefficient(sh, half_storage, base, 0u);
    if (degree > 0u) {
        const float x = dir.x, y = dir.y, z = dir.z;
        result = result - SH_C1 * y * sh_coefficient(sh, half_storage, base, 1u) + SH_C1 * z * sh_coefficient(sh, half_storage, base, 2u) -
                 SH_C1 * x * sh_coefficient(sh, half_storage, base, 3u);
        if (degree > 1u) {
            const float xx = x * x, yy = y * y, zz = z * z;
            const float xy = x * y, yz = y * z, xz = x * z;
            result = result + SH_C2[0] * xy * sh_coefficient(sh, half_storage, base, 4u) +
                     SH_C2[1] * yz * sh_coefficient(sh, half_storage, base, 5u) +
                     SH_C2[2] * (2.0 * zz - xx - yy) * sh_coefficient(sh, half_storage, base, 6u) +
                     SH_C2[3] * xz * sh_coefficient(sh, half_storage, base, 7u) +
                     SH_C2[4] * (xx - yy) * sh_coefficient(sh, half_storage, base, 8u);
            if (degree > 2u) {
                result = result + SH_C3[0] * y * (3.0 * xx - yy) * sh_coefficient(sh, half_storage, base, 9u) +
                         SH_C3[1] * xy * z * sh_coefficient(sh, half_storage, base, 10u) +
                         SH_C3[2] * y * (4.0 * zz - xx - yy) * sh_coefficient(sh, half_storage, base, 11u) +
                         SH_C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * sh_coefficient(sh, half_storage, base, 12u) +
                         SH_C3[4] * x * (4.0 * zz - xx - yy) * sh_coefficient(sh, half_storage, base, 13u) +
                         SH_C3[5] * z * (xx - yy) * sh_coefficient(sh, half_storage, base, 14u) +
                         SH_C3[6] * x * (xx - 3.0 * yy) * sh_coefficient(sh, half_storage, base, 15u);
            }
        }
    }
    return result;
}

#endif
