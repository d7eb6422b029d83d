// Per-Gaussian SH degree: which bands each Gaussian can do without, and zeroing them.
#include "vksplat/prune/sh_reduction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vksplat::prune {
namespace {

// Floats of one Gaussian's coefficients up to `degree` ([coefficient][rgb]).
size_t sh_floats(int degree) { return size_t(sh_coefficients_for_degree(degree)) * 3; }

// Dropping Gaussian `index`'s bands above `degree`, and what that costs (sh_reduction.hpp).
struct BandDrop {
    double cost = 0;
    uint32_t index = 0;
    uint8_t degree = 0;
};

}  // namespace

std::vector<uint8_t> sh_degrees_in_use(const GaussianCloud& cloud) {
    cloud.check_consistent();
    const size_t stride = sh_floats(cloud.sh_degree);
    std::vector<uint8_t> degrees(cloud.size(), 0);
    for (size_t i = 0; i < cloud.size(); ++i)
        for (int band = cloud.sh_degree; band > 0; --band) {
            const auto first = cloud.sh.begin() + std::ptrdiff_t(i * stride + sh_floats(band - 1));
            const auto last = cloud.sh.begin() + std::ptrdiff_t(i * stride + sh_floats(band));
            if (std::any_of(first, last, [](float c) { return c != 0.0f; })) {
                degrees[i] = uint8_t(band);
                break;
            }
        }
    return degrees;
}

std::vector<uint8_t> reduced_sh_degrees(const GaussianCloud& cloud, std::span<const double> weights, double share) {
    cloud.check_consistent();
    if (!(share >= 0.0 && share <= 1.0))
        throw std::invalid_argument("prune::reduced_sh_degrees: the share must lie in [0, 1]");
    if (!weights.empty() && weights.size() != cloud.size())
        throw std::invalid_argument("prune::reduced_sh_degrees: the weights are not of this cloud");
    const int top = cloud.sh_degree;
    const size_t stride = sh_floats(top);
    std::vector<BandDrop> drops;
    drops.reserve(cloud.size() * size_t(top));
    for (size_t i = 0; i < cloud.size(); ++i) {
        const double weight = weights.empty() ? 1.0 : weights[i];
        double energy = 0;  // of the bands above `degree`, summed from the top down
        for (int degree = top - 1; degree >= 0; --degree) {
            for (size_t f = sh_floats(degree); f < sh_floats(degree + 1); ++f)
                energy += double(cloud.sh[i * stride + f]) * double(cloud.sh[i * stride + f]);
            drops.push_back({weight * energy, uint32_t(i), uint8_t(degree)});
        }
    }
    // Costs never fall as a Gaussian's degree falls and ties go to the higher degree, so whatever
    // the cut, a Gaussian loses a band only with all those above it.
    const auto cheaper = [](const BandDrop& a, const BandDrop& b) {
        if (a.cost != b.cost) return a.cost < b.cost;
        if (a.degree != b.degree) return a.degree > b.degree;
        return a.index < b.index;
    };
    const auto count = std::min(drops.size(), size_t(std::llround(share * double(drops.size()))));
    std::nth_element(drops.begin(), drops.begin() + std::ptrdiff_t(count), drops.end(), cheaper);
    std::vector<uint8_t> degrees(cloud.size(), uint8_t(top));
    for (size_t d = 0; d < count; ++d) degrees[drops[d].index] = std::min(degrees[drops[d].index], drops[d].degree);
    return degrees;
}

GaussianCloud with_sh_degrees(const GaussianCloud& cloud, std::span<const uint8_t> degrees) {
    cloud.check_consistent();
    if (degrees.size() != cloud.size())
        throw std::invalid_argument("prune::with_sh_degrees: the degrees are not of this cloud");
    GaussianCloud out = cloud;
    const size_t stride = sh_floats(cloud.sh_degree);
    int highest = 0;
    for (size_t i = 0; i < cloud.size(); ++i) {
        const int degree = std::min<int>(degrees[i], cloud.sh_degree);
        highest = std::max(highest, degree);
        std::fill(out.sh.begin() + std::ptrdiff_t(i * stride + sh_floats(degree)),
                  out.sh.begin() + std::ptrdiff_t((i + 1) * stride), 0.0f);
    }
    return cloud.empty() ? out : out.with_sh_degree(highest);
}

GaussianCloud with_sh_share_dropped(const GaussianCloud& cloud, std::span<const double> weights, double share) {
    return with_sh_degrees(cloud, reduced_sh_degrees(cloud, weights, share));
}

}  // namespace vksplat::prune
