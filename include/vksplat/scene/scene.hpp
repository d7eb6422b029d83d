#pragma once
// GaussianCloud: a trained 3DGS scene on the host, stored as structure-of-arrays in the
// parameterisation the trainers save (log scales, logit opacity, raw quaternions, SH).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vksplat {

// Number of SH coefficients per colour channel for a degree (1, 4, 9, 16).
constexpr int sh_coefficients_for_degree(int degree) { return (degree + 1) * (degree + 1); }

struct GaussianCloud {
    int sh_degree = 0;                   // 0..3
    std::vector<float> positions;        // 3 per Gaussian: x, y, z (world)
    std::vector<float> log_scales;       // 3 per Gaussian: natural log of the standard deviations
    std::vector<float> rotations;        // 4 per Gaussian: quaternion w, x, y, z (not normalised)
    std::vector<float> opacity_logits;   // 1 per Gaussian: opacity = sigmoid(logit)
    // sh_coefficients_for_degree(sh_degree) * 3 per Gaussian, laid out [coefficient][rgb]:
    // coefficient 0 is the DC term (f_dc), then f_rest in band order. Colour = 0.5 + SH(dir).
    std::vector<float> sh;

    size_t size() const { return opacity_logits.size(); }
    bool empty() const { return opacity_logits.empty(); }
    int sh_coefficients() const { return sh_coefficients_for_degree(sh_degree); }

    // Resizes every array for n Gaussians (new entries are zero).
    void resize(size_t n);
    // Appends Gaussian `index` of `other` (which must have the same SH degree).
    void append(const GaussianCloud& other, size_t index);
    // Throws std::runtime_error if the arrays disagree in length or the SH degree is out of range.
    void check_consistent() const;

    // The Gaussians whose keep[i] is non-zero, in their original order.
    GaussianCloud subset(std::span<const uint8_t> keep) const;
    // The same scene with SH truncated (or zero-padded) to `degree`.
    GaussianCloud with_sh_degree(int degree) const;
    // Bytes the scene takes in the standard INRIA PLY layout (what a user downloads).
    size_t ply_bytes() const;
};

// What sanitize() changed, one count per cause. Gaussians are dropped when their geometry is
// undefined (non-finite position, rotation or scale, zero-length quaternion); values that only
// overflow are clamped; non-finite SH or opacity is replaced. See sanitize() for the rules.
struct SanitizeReport {
    size_t input_count = 0;
    size_t dropped_nonfinite_position = 0;  // non-finite or beyond kMaxCoordinate
    size_t dropped_nonfinite_rotation = 0;
    size_t dropped_zero_rotation = 0;
    size_t dropped_nonfinite_scale = 0;
    size_t clamped_scale = 0;             // log-scale outside [kMinLogScale, kMaxLogScale]
    size_t replaced_nonfinite_opacity = 0;  // NaN -> fully transparent; +-inf clamped
    size_t replaced_nonfinite_sh = 0;       // Gaussians with SH non-finite (set to 0) or huge (clamped)
    // Input index of each surviving Gaussian, in order; empty when nothing was dropped.
    std::vector<uint32_t> kept_indices;

    size_t dropped() const {
        return dropped_nonfinite_position + dropped_nonfinite_rotation + dropped_zero_rotation +
               dropped_nonfinite_scale;
    }
    size_t changed() const { return dropped() + clamped_scale + replaced_nonfinite_opacity + replaced_nonfinite_sh; }
    // One line per non-zero cause, or "clean" when nothing was changed.
    std::string summary() const;
};

// Log-scale bounds: 1e-10 .. 1e6 scene units. Outside them float covariances under/overflow.
inline constexpr float kMinLogScale = -23.0f;
inline constexpr float kMaxLogScale = 13.8f;
// Coordinates beyond this are treated like non-finite ones (float math overflows on them).
inline constexpr float kMaxCoordinate = 1e15f;
// SH coefficients are clamped to this magnitude (trained scenes stay far below 10).
inline constexpr float kMaxShMagnitude = 1e4f;
// Opacity logits are clamped to this magnitude so that sigmoid stays finite and exact.
inline constexpr float kMaxOpacityLogit = 30.0f;

// Makes a cloud safe to render: after it, no input can produce a NaN pixel.
SanitizeReport sanitize(GaussianCloud& cloud);

}  // namespace vksplat
