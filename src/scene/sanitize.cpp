// sanitize(): the one place a loaded scene is made safe to render. Trained scenes occasionally
// carry NaN/inf from diverged optimisation or broken converters; a single such Gaussian can turn
// every pixel it touches into NaN, so they are fixed (or dropped) before upload.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

// Quaternions shorter than this have no reliable direction: normalising them amplifies noise
// (or divides by zero), so their Gaussian's orientation is undefined.
constexpr double kMinQuaternionNorm = 1e-12;

bool all_finite(const float* values, size_t n) {
    return std::all_of(values, values + n, [](float v) { return std::isfinite(v); });
}

// A coordinate this far out is as undefined as infinity for float math: the view transform of
// 1e20 overflows to inf once squared, and inf/inf is NaN.
bool position_usable(const float* p) {
    return std::all_of(p, p + 3, [](float v) { return std::isfinite(v) && std::abs(v) <= kMaxCoordinate; });
}

enum class DropCause { none, position, rotation, zero_rotation, scale };

// The first reason Gaussian i's geometry is undefined, in the order the report lists them.
DropCause drop_cause(const GaussianCloud& cloud, size_t i) {
    if (!position_usable(&cloud.positions[i * 3])) return DropCause::position;
    const float* q = &cloud.rotations[i * 4];
    if (!all_finite(q, 4)) return DropCause::rotation;
    // In double: float squares of tiny or huge components would under/overflow.
    double norm2 = 0.0;
    for (int k = 0; k < 4; ++k) norm2 += static_cast<double>(q[k]) * q[k];
    if (std::sqrt(norm2) < kMinQuaternionNorm) return DropCause::zero_rotation;
    if (!all_finite(&cloud.log_scales[i * 3], 3)) return DropCause::scale;
    return DropCause::none;
}

// Clamps the log-scales of one Gaussian into the range where covariances stay finite.
bool clamp_scales(float* log_scales) {
    bool changed = false;
    for (int k = 0; k < 3; ++k) {
        const float clamped = std::clamp(log_scales[k], kMinLogScale, kMaxLogScale);
        changed |= clamped != log_scales[k];
        log_scales[k] = clamped;
    }
    return changed;
}

// NaN carries no information, so it becomes fully transparent (the Gaussian disappears rather than
// painting an arbitrary colour); infinities and huge finite logits keep their sign.
bool fix_opacity(float& logit) {
    const float fixed = std::isnan(logit) ? -kMaxOpacityLogit : std::clamp(logit, -kMaxOpacityLogit, kMaxOpacityLogit);
    const bool changed = fixed != logit;  // also true for NaN, which equals nothing
    logit = fixed;
    return changed;
}

// Non-finite SH becomes 0 (no view-dependent colour); huge values are clamped so that the sum
// of 16 terms cannot overflow.
bool fix_sh(float* values, size_t n) {
    bool changed = false;
    for (size_t k = 0; k < n; ++k) {
        const float fixed = std::isfinite(values[k]) ? std::clamp(values[k], -kMaxShMagnitude, kMaxShMagnitude) : 0.0f;
        changed |= fixed != values[k] || !std::isfinite(values[k]);
        values[k] = fixed;
    }
    return changed;
}

// Moves Gaussian `from` to slot `to` (to <= from) within the same cloud.
void move_gaussian(GaussianCloud& cloud, size_t from, size_t to, size_t sh_per) {
    if (from == to) return;
    std::copy_n(&cloud.positions[from * 3], 3, &cloud.positions[to * 3]);
    std::copy_n(&cloud.log_scales[from * 3], 3, &cloud.log_scales[to * 3]);
    std::copy_n(&cloud.rotations[from * 4], 4, &cloud.rotations[to * 4]);
    cloud.opacity_logits[to] = cloud.opacity_logits[from];
    std::copy_n(&cloud.sh[from * sh_per], sh_per, &cloud.sh[to * sh_per]);
}

// Shortest decimal form of a bound, for the summary ("13.8", not "13.800000").
std::string number(float value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

}  // namespace

SanitizeReport sanitize(GaussianCloud& cloud) {
    cloud.check_consistent();
    SanitizeReport report;
    report.input_count = cloud.size();
    const size_t sh_per = static_cast<size_t>(cloud.sh_coefficients()) * 3;

    // Kept Gaussians are compacted to the front in their original order.
    size_t kept = 0;
    std::vector<uint32_t> kept_indices;
    kept_indices.reserve(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) {
        switch (drop_cause(cloud, i)) {
            case DropCause::position: ++report.dropped_nonfinite_position; continue;
            case DropCause::rotation: ++report.dropped_nonfinite_rotation; continue;
            case DropCause::zero_rotation: ++report.dropped_zero_rotation; continue;
            case DropCause::scale: ++report.dropped_nonfinite_scale; continue;
            case DropCause::none: break;
        }
        report.clamped_scale += clamp_scales(&cloud.log_scales[i * 3]) ? 1 : 0;
        report.replaced_nonfinite_opacity += fix_opacity(cloud.opacity_logits[i]) ? 1 : 0;
        report.replaced_nonfinite_sh += fix_sh(&cloud.sh[i * sh_per], sh_per) ? 1 : 0;
        move_gaussian(cloud, i, kept, sh_per);
        kept_indices.push_back(static_cast<uint32_t>(i));
        ++kept;
    }
    cloud.resize(kept);
    if (report.dropped() > 0) report.kept_indices = std::move(kept_indices);
    return report;
}

std::string SanitizeReport::summary() const {
    if (changed() == 0) return "clean";
    std::string out;
    const auto line = [&out](size_t count, const std::string& what) {
        if (count == 0) return;
        if (!out.empty()) out += "\n";
        out += std::to_string(count) + " " + what;
    };
    line(dropped_nonfinite_position, "Gaussians dropped: non-finite position or a coordinate beyond +-" + number(kMaxCoordinate));
    line(dropped_nonfinite_rotation, "Gaussians dropped: non-finite rotation");
    line(dropped_zero_rotation, "Gaussians dropped: zero-length rotation quaternion");
    line(dropped_nonfinite_scale, "Gaussians dropped: non-finite scale");
    line(clamped_scale, "Gaussians with log-scales clamped to [" + number(kMinLogScale) + ", " +
                            number(kMaxLogScale) + "]");
    line(replaced_nonfinite_opacity, "Gaussians with opacity logit NaN (made transparent) or beyond +-" +
                                         number(kMaxOpacityLogit) + " (clamped)");
    line(replaced_nonfinite_sh, "Gaussians with non-finite SH coefficients (set to 0) or beyond +-" + number(kMaxShMagnitude) + " (clamped)");
    return out;
}

}  // namespace vksplat
