// SH coefficients rounded to fewer bits of SPZ's byte (sh_precision.hpp).
#include "vksplat/prune/sh_precision.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "vksplat/error.hpp"

namespace vksplat::prune {
namespace {

// SPZ's byte of a coefficient, rounded to a multiple of 2^(8 - bits) as the reference encoder's
// quantizeSH does (round, bucket, clamp), and the value that byte stands for.
float rounded(float coefficient, int bits) {
    const double byte = std::clamp(std::round(double(coefficient) * 128.0 + 128.0), 0.0, 255.0);
    const double bucket = double(1 << (8 - bits));
    const double kept = std::clamp(std::floor((byte + bucket / 2.0) / bucket) * bucket, 0.0, 255.0);
    return float((kept - 128.0) / 128.0);
}

}  // namespace

void check_sh_precision(const ShPrecision& precision) {
    for (int bits : {precision.degree1_bits, precision.higher_bits})
        if (bits < 1 || bits > 8)
            throw InputError("--sh-bits " + std::to_string(precision.degree1_bits) + "," +
                                 std::to_string(precision.higher_bits),
                             "SH bits must be whole numbers from 1 to 8 (degree 1, then degrees 2 and 3)");
}

GaussianCloud with_sh_precision(const GaussianCloud& cloud, const ShPrecision& precision) {
    check_sh_precision(precision);
    GaussianCloud out = cloud;
    const size_t coefficients = size_t(cloud.sh_coefficients());
    for (size_t i = 0; i < cloud.size(); ++i)
        for (size_t k = 1; k < coefficients; ++k) {
            const int bits = k <= 3 ? precision.degree1_bits : precision.higher_bits;
            for (size_t c = 0; c < 3; ++c) {
                float& value = out.sh[(i * coefficients + k) * 3 + c];
                value = rounded(value, bits);
            }
        }
    return out;
}

}  // namespace vksplat::prune
