#if !defined(FIXED_POINT_SUMS)
#error define FIXED_POINT_SUMS and declare the push constants before including preprocess_backward.glsl
#endif
// Preprocess backward, included by preprocess_backward.comp (the blend backward summed each
// splat's gradients as floats) and preprocess_backward_fixed.comp (as 64-bit integers,
// SPLAT_GRAD_FIXED_SCALE units per 1.0, read here as they are: no pass turns them into floats
// first, nor holds a float copy). One thread per Gaussian. From the gradients the blend backward
// gathered for each splat (projected mean, conic, opacity, colour), the gradients of the raw
// position, log-scales, quaternion and opacity logit, through every step preprocess_trainable.comp
// and preprocess.glsl take (sigmoid, exp, quaternion normalisation, rotation and covariance,
// EWA projection with its clamped Jacobian, the 0.3 px low-pass, the conic's inverse, the SH
// colour with its clamp at 0 and its view direction). Exact derivatives of that forward: where
// the Jacobian's lateral position is clamped it no longer moves with the position, so it passes
// no gradient there. Gaussians the frame did not draw get zeros.
// The SH coefficients' gradients are basis(view direction) x d L / d colour: this pass leaves
// each Gaussian's direction and colour gradient in pc.sh_steps, and sh_backward.comp takes them
// one float a thread. In one pass they cost more than the two: this one needs ~200 registers,
// which leaves too few threads on a multiprocessor to keep the SH block's loads in flight.
// In a training step (pc.adam set) each gradient goes straight into Adam (adam.glsl) with the
// learning rate of its parameter group, and 3DGS-MCMC's regularisers join it here, as they reach
// every Gaussian, seen or not; otherwise the gradients are written to pc.grads. A Gaussian with a
// non-finite gradient sets STEP_NONFINITE in the step status and, in a training step, does not
// step: its parameters and moments stay as they were, while the others step (the host counts the
// step as skipped).
#include "shaders/common/buffers.h"
#include "vksplat/constants.hpp"
#include "shaders/render/frame.h"
#include "shaders/render/sh.glsl"
#include "shaders/train/differentiable_renderer.h"
#include "shaders/common/gaussian_shape.glsl"
#include "shaders/train/adam.glsl"

layout(local_size_x = 256) in;

// The blend backward's total k (of SPLAT_GRAD_STRIDE per Gaussian).
float splat_grad(uint k) {
#if FIXED_POINT_SUMS
    return float(Int64s(pc.splat_grads).v[k]) * (1.0 / SPLAT_GRAD_FIXED_SCALE);  // a power of 2: exact
#else
    return pc.splat_grads.v[k];
#endif
}

// d L / d (w, x, y, z) of a unit quaternion, from d L / d R (g[column][row], GLSL's order).
vec4 rotation_backward(vec4 q, mat3 g) {
    const float w = q.x, x = q.y, y = q.z, z = q.w;
    // Row r, column c of the gradient.
#define G(r, c) g[c][r]
    return 2.0 * vec4(
        -z * G(0, 1) + y * G(0, 2) + z * G(1, 0) - x * G(1, 2) - y * G(2, 0) + x * G(2, 1),
        y * G(0, 1) + z * G(0, 2) + y * G(1, 0) - 2.0 * x * G(1, 1) - w * G(1, 2) + z * G(2, 0) + w * G(2, 1) -
            2.0 * x * G(2, 2),
        -2.0 * y * G(0, 0) + x * G(0, 1) + w * G(0, 2) + x * G(1, 0) + z * G(1, 2) - w * G(2, 0) + z * G(2, 1) -
            2.0 * y * G(2, 2),
        -2.0 * z * G(0, 0) - w * G(0, 1) + x * G(0, 2) + w * G(1, 0) - 2.0 * z * G(1, 1) + y * G(1, 2) +
            x * G(2, 0) + y * G(2, 1));
#undef G
}

// d (basis function k) / d (x, y, z) at unit direction `dir`, for k from 1 to 15 (the constant
// band has none).
vec3 sh_basis_derivative(uint k, vec3 dir) {
    const float x = dir.x, y = dir.y, z = dir.z;
    const float xx = x * x, yy = y * y, zz = z * z;
    switch (k) {
        case 1u: return vec3(0.0, -SH_C1, 0.0);
        case 2u: return vec3(0.0, 0.0, SH_C1);
        case 3u: return vec3(-SH_C1, 0.0, 0.0);
        case 4u: return SH_C2[0] * vec3(y, x, 0.0);
        case 5u: return SH_C2[1] * vec3(0.0, z, y);
        case 6u: return SH_C2[2] * vec3(-2.0 * x, -2.0 * y, 4.0 * z);
        case 7u: return SH_C2[3] * vec3(z, 0.0, x);
        case 8u: return SH_C2[4] * vec3(2.0 * x, -2.0 * y, 0.0);
        case 9u: return SH_C3[0] * vec3(6.0 * x * y, 3.0 * xx - 3.0 * yy, 0.0);
        case 10u: return SH_C3[1] * vec3(y * z, x * z, x * y);
        case 11u: return SH_C3[2] * vec3(-2.0 * x * y, 4.0 * zz - xx - 3.0 * yy, 8.0 * y * z);
        case 12u: return SH_C3[3] * vec3(-6.0 * x * z, -6.0 * y * z, 6.0 * zz - 3.0 * xx - 3.0 * yy);
        case 13u: return SH_C3[4] * vec3(4.0 * zz - 3.0 * xx - yy, -2.0 * x * y, 8.0 * x * z);
        case 14u: return SH_C3[5] * vec3(2.0 * x * z, -2.0 * y * z, xx - yy);
        default: return SH_C3[6] * vec3(3.0 * xx - 3.0 * yy, -6.0 * x * y, 0.0);
    }
}

// d L / d direction of the SH colour at `dir`, the coefficients starting at raw[base]. A loop,
// not unrolled, over a coefficient index every thread shares (the frame's degree): no divergence,
// and none of the 16 derivatives held at once. Unrolled into an array they cost 48 registers of a
// kernel that then held 238 (H200), one workgroup to a multiprocessor.
vec3 sh_direction_backward(uint base, uint degree, vec3 dir, vec3 dl_dcolor) {
    const uint count = (degree + 1u) * (degree + 1u);
    vec3 dl_ddir = vec3(0.0);
    [[dont_unroll]] for (uint k = 1u; k < count; ++k) {
        const uint at = base + 3u * k;
        const vec3 coefficient = vec3(pc.raw.v[at], pc.raw.v[at + 1u], pc.raw.v[at + 2u]);
        dl_ddir += sh_basis_derivative(k, dir) * dot(coefficient, dl_dcolor);
    }
    return dl_ddir;
}

bool fused() { return (pc.adam.x | pc.adam.y) != 0u; }

// Where float k (0 to 10) of Gaussian i's geometry sits: position (3), log-scale (3), quaternion
// (4), opacity logit (1).
uint geometry_at(uint n, uint i, uint k) {
    if (k < 3u) return positions_offset(n) + 3u * i + k;
    if (k < 6u) return log_scales_offset(n) + 3u * i + k - 3u;
    if (k < 10u) return rotations_offset(n) + 4u * i + k - 6u;
    return opacities_offset(n) + i;
}

float geometry_rate(AdamSettings s, uint k) {
    return k < 3u ? s.lr_position : k < 6u ? s.lr_scale : k < 10u ? s.lr_rotation : s.lr_opacity;
}

// Gaussian i's geometry gradients `g`: into Adam, with the regularisers (adam_step.h), which only
// a training step adds, or written out. Every state is loaded before any is stored (adam.glsl).
void take_geometry(AdamSettings s, uint n, uint i, float g[11]) {
    if (!fused()) {
        [[unroll]] for (uint k = 0u; k < 11u; ++k) pc.grads.v[geometry_at(n, i, k)] = g[k];
        return;
    }
    AdamState state[11];
    [[unroll]] for (uint k = 0u; k < 11u; ++k) state[k] = adam_load(s, pc.raw, geometry_at(n, i, k));
    [[unroll]] for (uint k = 0u; k < 11u; ++k) {
        float gradient = g[k];
        if (k >= 3u && k < 6u) gradient += s.scale_regularization * exp(state[k].param);
        if (k == 10u) {
            const float opacity = sigmoid(state[k].param);
            gradient += s.opacity_regularization * opacity * (1.0 - opacity);
        }
        adam_store(s, pc.raw, geometry_at(n, i, k), state[k], gradient, geometry_rate(s, k));
    }
}

bool finite(float v) { return !isnan(v) && !isinf(v); }
bool finite(vec3 v) { return finite(v.x) && finite(v.y) && finite(v.z); }

// What a Gaussian's SH coefficients' gradients follow from: basis(dir) x d L / d colour.
struct ShStep {
    vec3 dir;
    vec3 dl_dcolor;  // zero for a Gaussian the frame did not draw
    bool steps;      // false: a training step leaves this Gaussian as it is (a non-finite gradient)
};

// Gaussian i's gradients but its SH coefficients', taken (into Adam or written); returns what its
// SH coefficients' need.
ShStep backward(AdamSettings adam, CameraParams cam, uint n, uint i) {
    ShStep sh = ShStep(vec3(0.0), vec3(0.0), true);
    if (pc.tiles_touched.v[i] == 0u) {
        float zeros[11] = float[11](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        take_geometry(adam, n, i, zeros);
        return sh;
    }
    const uint sg = i * SPLAT_GRAD_STRIDE;
    const vec2 dl_dmean = vec2(splat_grad(sg + SPLAT_GRAD_MEAN), splat_grad(sg + SPLAT_GRAD_MEAN + 1u));
    // The reference densifies by the gradient of the mean in NDC (pixels = (ndc + 1) size / 2 - 0.5),
    // so its threshold of 0.0002 holds at any resolution.
    const uint d = i * DENSIFY_STRIDE;
    pc.densify.v[d + DENSIFY_GRAD_SUM] += length(dl_dmean * 0.5 * vec2(cam.size.xy));
    pc.densify.v[d + DENSIFY_VIEWS] += 1.0;
    pc.densify.v[d + DENSIFY_MAX_RADIUS] = max(pc.densify.v[d + DENSIFY_MAX_RADIUS], pc.means_depth.v[i].w);
    const vec3 dl_dconic = vec3(splat_grad(sg + SPLAT_GRAD_CONIC), splat_grad(sg + SPLAT_GRAD_CONIC + 1u),
                                splat_grad(sg + SPLAT_GRAD_CONIC + 2u));
    const float dl_dopacity = splat_grad(sg + SPLAT_GRAD_OPACITY);
    vec3 dl_dcolor = vec3(splat_grad(sg + SPLAT_GRAD_COLOR), splat_grad(sg + SPLAT_GRAD_COLOR + 1u),
                          splat_grad(sg + SPLAT_GRAD_COLOR + 2u));

    const uint po = positions_offset(n) + 3u * i, so = log_scales_offset(n) + 3u * i;
    const uint ro = rotations_offset(n) + 4u * i, oo = opacities_offset(n) + i;
    const uint sho = sh_offset(n) + 3u * cam.sh_stride * i;
    const vec3 p = vec3(pc.raw.v[po], pc.raw.v[po + 1u], pc.raw.v[po + 2u]);
    const vec3 scale = exp(vec3(pc.raw.v[so], pc.raw.v[so + 1u], pc.raw.v[so + 2u]));
    const vec4 q_raw = vec4(pc.raw.v[ro], pc.raw.v[ro + 1u], pc.raw.v[ro + 2u], pc.raw.v[ro + 3u]);
    const float q_length = length(q_raw);
    const vec4 q = q_raw / q_length;
    const float opacity = sigmoid(pc.raw.v[oo]);

    // Colour: SH + 0.5 clamped at 0 passes no gradient where it clamped.
    const vec3 to_gaussian = p - cam.position.xyz;
    const float distance = length(to_gaussian);
    const vec3 dir = to_gaussian / distance;
    const vec3 sh_color = eval_sh_in_place(ShSource(Floats(pc.raw), false, false, sho), cam.sh_degree, dir) + COLOR_OFFSET;
    dl_dcolor *= vec3(greaterThanEqual(sh_color, vec3(0.0)));
    const vec3 dl_ddir = sh_direction_backward(sho, cam.sh_degree, dir, dl_dcolor);
    sh.dir = dir;
    sh.dl_dcolor = dl_dcolor;
    vec3 dl_dp = (dl_ddir - dir * dot(dir, dl_ddir)) / distance;

    // Projection of the mean.
    const mat3 world_to_view = transpose(mat3(cam.view_row0.xyz, cam.view_row1.xyz, cam.view_row2.xyz));
    const vec3 view = world_to_view * p + vec3(cam.view_row0.w, cam.view_row1.w, cam.view_row2.w);
    const float fx = cam.focal_principal.x, fy = cam.focal_principal.y;
    const float z = view.z, z2 = z * z;
    vec3 dl_dview = vec3(fx / z * dl_dmean.x, fy / z * dl_dmean.y,
                         -fx * view.x / z2 * dl_dmean.x - fy * view.y / z2 * dl_dmean.y);

    // Covariance: Sigma = M M^T with M = R S.
    const mat3 rotation = rotation_matrix(q);
    const mat3 m = rotation * mat3(scale.x, 0.0, 0.0, 0.0, scale.y, 0.0, 0.0, 0.0, scale.z);
    const mat3 sigma = m * transpose(m);
    // EWA, as preprocess.glsl: the lateral positions are clamped before the Jacobian.
    const float ux = view.x / z, uy = view.y / z;
    const float ux_c = clamp(ux, -cam.jacobian_limits.x, cam.jacobian_limits.y);
    const float uy_c = clamp(uy, -cam.jacobian_limits.z, cam.jacobian_limits.w);
    const mat3 jacobian = transpose(mat3(vec3(fx / z, 0.0, -fx * ux_c / z), vec3(0.0, fy / z, -fy * uy_c / z),
                                         vec3(0.0)));
    const mat3 t = jacobian * world_to_view;
    const mat3 cov = t * sigma * transpose(t);
    const float a = cov[0][0] + LOW_PASS_FILTER, b = cov[1][0], c = cov[1][1] + LOW_PASS_FILTER;
    const float det = a * c - b * b;
    // Conic = inverse of [[a, b], [b, c]]: d L / d cov2 = -C G C with G the conic's gradient
    // as a symmetric matrix (the off-diagonal scalar appears twice in the power).
    const mat2 conic = mat2(c, -b, -b, a) / det;
    const mat2 g_conic = mat2(dl_dconic.x, 0.5 * dl_dconic.y, 0.5 * dl_dconic.y, dl_dconic.z);
    const mat2 g_cov2 = -(conic * g_conic * conic);
    mat3 g_cov = mat3(0.0);
    g_cov[0][0] = g_cov2[0][0];
    g_cov[0][1] = g_cov2[0][1];
    g_cov[1][0] = g_cov2[1][0];
    g_cov[1][1] = g_cov2[1][1];
    // cov = T Sigma T^T: d/dSigma = T^T G T, d/dT = 2 G T Sigma (G and Sigma symmetric).
    const mat3 g_sigma = transpose(t) * g_cov * t;
    const mat3 g_t = 2.0 * g_cov * t * sigma;
    const mat3 g_jacobian = g_t * transpose(world_to_view);
    // Jacobian entries (row, column) = g_jacobian[column][row].
    const float g_j00 = g_jacobian[0][0], g_j11 = g_jacobian[1][1];
    const float g_j02 = g_jacobian[2][0], g_j12 = g_jacobian[2][1];
    const bool x_free = ux == ux_c, y_free = uy == uy_c;
    dl_dview.z += g_j00 * (-fx / z2) + g_j11 * (-fy / z2);
    // J02 = -fx ux_c / z, with ux_c = x / z where unclamped.
    dl_dview.z += g_j02 * (fx * ux_c / z2) + g_j12 * (fy * uy_c / z2);
    if (x_free) {
        dl_dview.x += g_j02 * (-fx / z2);
        dl_dview.z += g_j02 * (fx * view.x / (z2 * z));
    }
    if (y_free) {
        dl_dview.y += g_j12 * (-fy / z2);
        dl_dview.z += g_j12 * (fy * view.y / (z2 * z));
    }
    dl_dp += transpose(world_to_view) * dl_dview;

    // Sigma = M M^T: d/dM = 2 G M; M = R diag(s): column k of M is s_k times column k of R.
    const mat3 g_m = 2.0 * g_sigma * m;
    const vec3 dl_dscale = vec3(dot(g_m[0], rotation[0]), dot(g_m[1], rotation[1]), dot(g_m[2], rotation[2]));
    const mat3 g_rotation = mat3(g_m[0] * scale.x, g_m[1] * scale.y, g_m[2] * scale.z);
    const vec4 dl_dq = rotation_backward(q, g_rotation);
    const vec4 dl_dq_raw = (dl_dq - q * dot(q, dl_dq)) / q_length;
    const vec3 dl_dlog_scale = dl_dscale * scale;
    const float dl_dlogit = dl_dopacity * opacity * (1.0 - opacity);

    const bool all_finite = finite(dl_dp) && finite(dl_dlog_scale) && finite(dl_dq_raw.xyz) &&
                            finite(dl_dq_raw.w) && finite(dl_dlogit) && finite(dl_dcolor) && finite(dl_ddir);
    if (!all_finite) atomicOr(pc.status.v[0], STEP_NONFINITE);
    if (fused() && !all_finite) {
        sh.steps = false;
        return sh;
    }
    take_geometry(adam, n, i,
                  float[11](dl_dp.x, dl_dp.y, dl_dp.z, dl_dlog_scale.x, dl_dlog_scale.y, dl_dlog_scale.z, dl_dq_raw.x,
                            dl_dq_raw.y, dl_dq_raw.z, dl_dq_raw.w, dl_dlogit));
    return sh;
}

void main() {
    const CameraParams cam = pc.camera.c;
    const uint n = cam.gaussian_count;
    // A frame that overflowed walked cut lists: its gradients are wrong, and it is run again, so
    // it adds nothing to the densification sums either (they would count the step twice). A step
    // queued behind one that overflowed does the same (parameter_layout.h, the overflow mark).
    const bool overflowed = pc.counters.v[COUNTER_ENTRIES_NEEDED] > cam.entry_capacity;
    if (overflowed || pc.status.v[STATUS_OVERFLOW_MARK] != 0u) {
        if (gl_GlobalInvocationID.x == 0u) {
            atomicOr(pc.status.v[0], STEP_OVERFLOWED);
            if (overflowed) atomicOr(pc.status.v[STATUS_OVERFLOW_MARK], 1u);
        }
        return;
    }
    // The fixed-point sums lost a gradient they could not hold (parameter_layout.h): nothing steps.
    if (fused() && (pc.status.v[0] & STEP_NONFINITE_SUMS) != 0u) return;
    AdamSettings adam;
    if (fused()) adam = AdamSettingsBuffer(pc.adam).s;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const ShStep sh = backward(adam, cam, n, i);
        pc.sh_steps.v[2u * i] = vec4(sh.dir, sh.steps ? 1.0 : 0.0);
        pc.sh_steps.v[2u * i + 1u] = vec4(sh.dl_dcolor, 0.0);
    }
}
