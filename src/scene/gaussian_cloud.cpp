// GaussianCloud's bookkeeping: sizing, copying Gaussians between clouds, SH degree changes.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "vksplat/scene/scene.hpp"

namespace vksplat {
namespace {

constexpr size_t kPositionFloats = 3;
constexpr size_t kScaleFloats = 3;
constexpr size_t kRotationFloats = 4;

size_t sh_floats(int degree) { return static_cast<size_t>(sh_coefficients_for_degree(degree)) * 3; }

void check_degree(int degree, const char* what) {
    if (degree < 0 || degree > 3)
        throw std::invalid_argument(std::string(what) + ": SH degree " + std::to_string(degree) +
                                    " is outside 0..3");
}

// Appends the `per` floats of item `index` in `from` to `to`.
void append_item(std::vector<float>& to, const std::vector<float>& from, size_t index, size_t per) {
    const auto first = from.begin() + static_cast<std::ptrdiff_t>(index * per);
    to.insert(to.end(), first, first + static_cast<std::ptrdiff_t>(per));
}

}  // namespace

void GaussianCloud::resize(size_t n) {
    check_degree(sh_degree, "GaussianCloud::resize");
    positions.resize(n * kPositionFloats, 0.0f);
    log_scales.resize(n * kScaleFloats, 0.0f);
    rotations.resize(n * kRotationFloats, 0.0f);
    opacity_logits.resize(n, 0.0f);
    sh.resize(n * sh_floats(sh_degree), 0.0f);
}

void GaussianCloud::append(const GaussianCloud& other, size_t index) {
    if (other.sh_degree != sh_degree)
        throw std::invalid_argument("GaussianCloud::append: SH degree " + std::to_string(other.sh_degree) +
                                    " into a cloud of degree " + std::to_string(sh_degree));
    if (index >= other.size())
        throw std::out_of_range("GaussianCloud::append: index " + std::to_string(index) + " of a cloud of " +
                                std::to_string(other.size()) + " Gaussians");
    append_item(positions, other.positions, index, kPositionFloats);
    append_item(log_scales, other.log_scales, index, kScaleFloats);
    append_item(rotations, other.rotations, index, kRotationFloats);
    append_item(opacity_logits, other.opacity_logits, index, 1);
    append_item(sh, other.sh, index, sh_floats(sh_degree));
}

void GaussianCloud::check_consistent() const {
    if (sh_degree < 0 || sh_degree > 3)
        throw std::runtime_error("Gaussian cloud: SH degree " + std::to_string(sh_degree) + " is outside 0..3");
    const size_t n = size();
    const auto check = [n](const std::vector<float>& values, size_t per, const char* name) {
        if (values.size() != n * per)
            throw std::runtime_error("Gaussian cloud: " + std::string(name) + " has " +
                                     std::to_string(values.size()) + " values for " + std::to_string(n) +
                                     " Gaussians (expected " + std::to_string(n * per) + ")");
    };
    check(positions, kPositionFloats, "positions");
    check(log_scales, kScaleFloats, "log_scales");
    check(rotations, kRotationFloats, "rotations");
    check(sh, sh_floats(sh_degree), "sh");
}

GaussianCloud GaussianCloud::subset(std::span<const uint8_t> keep) const {
    check_consistent();
    if (keep.size() != size())
        throw std::invalid_argument("GaussianCloud::subset: mask of " + std::to_string(keep.size()) +
                                    " entries for " + std::to_string(size()) + " Gaussians");
    GaussianCloud out;
    out.sh_degree = sh_degree;
    const size_t kept = static_cast<size_t>(std::count_if(keep.begin(), keep.end(), [](uint8_t k) { return k != 0; }));
    out.positions.reserve(kept * kPositionFloats);
    out.log_scales.reserve(kept * kScaleFloats);
    out.rotations.reserve(kept * kRotationFloats);
    out.opacity_logits.reserve(kept);
    out.sh.reserve(kept * sh_floats(sh_degree));
    for (size_t i = 0; i < keep.size(); ++i)
        if (keep[i] != 0) out.append(*this, i);
    return out;
}

GaussianCloud GaussianCloud::with_sh_degree(int degree) const {
    check_consistent();
    check_degree(degree, "GaussianCloud::with_sh_degree");
    GaussianCloud out = *this;
    out.sh_degree = degree;
    out.sh.assign(size() * sh_floats(degree), 0.0f);
    // Coefficients are [coefficient][rgb], so the lower bands are a prefix of each Gaussian's block.
    const size_t from = sh_floats(sh_degree), to = sh_floats(degree), common = std::min(from, to);
    for (size_t i = 0; i < size(); ++i)
        std::copy_n(sh.begin() + static_cast<std::ptrdiff_t>(i * from), common,
                    out.sh.begin() + static_cast<std::ptrdiff_t>(i * to));
    return out;
}

}  // namespace vksplat
