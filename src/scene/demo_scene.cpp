#include "vksplat/scene/demo_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

// Bit-identical output needs every multiply and add rounded on its own, never fused. GCC in ISO
// C++ mode (how vksplat builds) and MSVC's /fp:precise do not fuse; Clang fuses unless told.
// (-ffast-math or -ffp-contract=fast overrides this; the fingerprint test in
// tests/scene/demo_scene_test.cpp would catch it.)
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

namespace vksplat {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kShC0 = 0.28209479177387814;  // the degree-0 SH basis function

// ---- Portable arithmetic ------------------------------------------------------------------------
// libm's sin, cos and log may differ in the last bit between platforms; these use only +, -, *, /
// and exact operations (floor, frexp), so they give the same bits everywhere. Accuracy is within
// a few ulp, far more than a demo scene needs.

constexpr double inverse_factorial(int n) {
    double f = 1.0;  // exact: 18! < 2^53
    for (int i = 2; i <= n; ++i) f *= i;
    return 1.0 / f;
}

// Taylor coefficients of sin(r) / r and cos(r) in r^2; truncation error < 1e-18 for |r| <= pi/4.
constexpr std::array<double, 9> kSinSeries = [] {
    std::array<double, 9> c{};
    for (int i = 0; i < 9; ++i) c[i] = (i % 2 ? -1.0 : 1.0) * inverse_factorial(2 * i + 1);
    return c;
}();
constexpr std::array<double, 10> kCosSeries = [] {
    std::array<double, 10> c{};
    for (int i = 0; i < 10; ++i) c[i] = (i % 2 ? -1.0 : 1.0) * inverse_factorial(2 * i);
    return c;
}();

template <size_t N>
double horner(const std::array<double, N>& c, double x) {
    double acc = c[N - 1];
    for (size_t i = N - 1; i-- > 0;) acc = acc * x + c[i];
    return acc;
}

struct SinCos {
    double sin, cos;
};

SinCos sin_cos(double x) {
    // x = k pi/2 + r with |r| <= pi/4. pi/2 is split in two (fdlibm's constants) so that k times
    // the high part is exact for the small k this file needs.
    constexpr double kPiOver2High = 1.57079632673412561417e+00;  // first 33 bits of pi/2
    constexpr double kPiOver2Low = 6.07710050650619224932e-11;   // pi/2 - kPiOver2High
    const double k = std::floor(x * (2.0 / kPi) + 0.5);
    const double r = (x - k * kPiOver2High) - k * kPiOver2Low;
    const double s = r * horner(kSinSeries, r * r);
    const double c = horner(kCosSeries, r * r);
    switch (static_cast<long long>(k) & 3) {
        case 0: return {s, c};
        case 1: return {c, -s};
        case 2: return {-s, -c};
        default: return {-c, s};
    }
}

// Natural logarithm of a positive, finite, normal x.
double log_positive(double x) {
    constexpr double kLn2 = 0.69314718055994530942;
    constexpr double kSqrtHalf = 0.70710678118654752440;
    int e = 0;
    double m = std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1): exact
    if (m < kSqrtHalf) {
        m *= 2.0;
        --e;
    }
    // log m = 2 atanh(s) = 2 (s + s^3/3 + s^5/5 + ...) with |s| < 0.172: terms past s^23 < 1e-18.
    const double s = (m - 1.0) / (m + 1.0);
    double acc = 1.0 / 23.0;
    for (int k = 21; k >= 1; k -= 2) acc = acc * (s * s) + 1.0 / k;
    return 2.0 * s * acc + e * kLn2;
}

double logit(double p) { return log_positive(p / (1.0 - p)); }

// std::mt19937's output sequence is fixed by the standard; std:: distributions are not, so the
// distributions are written here. Every draw is its own statement: the order in which function
// arguments are evaluated is unspecified, so f(rng.uniform(), rng.uniform()) is not portable.
class Random {
public:
    explicit Random(uint32_t seed) : engine_(seed) {}

    // Uniform in [0, 1) with 53 random bits from two 32-bit outputs.
    double uniform() {
        const double high = static_cast<double>(engine_() >> 5);  // 27 bits
        const double low = static_cast<double>(engine_() >> 6);   // 26 bits
        return (high * 67108864.0 + low) / 9007199254740992.0;
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    // Approximately standard normal: the sum of four uniforms, centred and scaled to variance 1
    // (Irwin-Hall; tails cut at 3.46 sigma). It needs no logarithm, and a demo scene needs neither
    // exact tails nor the 24 engine calls per value that more terms would cost.
    double normal() {
        constexpr double kSqrt3 = 1.7320508075688772;
        double sum = 0.0;
        for (int i = 0; i < 4; ++i) sum += static_cast<double>(engine_()) / 4294967296.0;
        return (sum - 2.0) * kSqrt3;
    }

private:
    std::mt19937 engine_;
};

// ---- Building Gaussians -------------------------------------------------------------------------

using Vec3 = glm::dvec3;

struct Quaternion {
    double w, x, y, z;
};

// The rotation whose columns are the right-handed orthonormal axes u, v, n (Shepperd's method,
// which stays accurate for every rotation).
Quaternion quaternion_from_axes(const Vec3& u, const Vec3& v, const Vec3& n) {
    const double m00 = u.x, m10 = u.y, m20 = u.z;
    const double m01 = v.x, m11 = v.y, m21 = v.z;
    const double m02 = n.x, m12 = n.y, m22 = n.z;
    const double trace = m00 + m11 + m22;
    if (trace > 0.0) {
        const double s = 2.0 * std::sqrt(trace + 1.0);
        return {0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s};
    }
    if (m00 > m11 && m00 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m00 - m11 - m22);
        return {(m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s};
    }
    if (m11 > m22) {
        const double s = 2.0 * std::sqrt(1.0 + m11 - m00 - m22);
        return {(m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s};
    }
    const double s = 2.0 * std::sqrt(1.0 + m22 - m00 - m11);
    return {(m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s};
}

Vec3 mix(const Vec3& a, const Vec3& b, double t) { return a + (b - a) * t; }

// One Gaussian in natural units, before conversion to the stored parameterisation.
struct Splat {
    Vec3 position;
    Vec3 sigma;  // standard deviations along the rotation's axes
    Quaternion rotation;
    double opacity;
    Vec3 colour;  // the colour seen along the DC term alone
};

// Appends `s` to `cloud` (SH degree 3), drawing small random view-dependent SH terms. The higher
// bands get smaller amplitudes, like trained scenes, so the colour stays close to `s.colour`.
void append(GaussianCloud& cloud, const Splat& s, Random& rng) {
    constexpr double kBandAmplitude[] = {0.0, 0.05, 0.025, 0.012};
    const std::array<double, 3> position = {s.position.x, s.position.y, s.position.z};
    const std::array<double, 3> sigma = {s.sigma.x, s.sigma.y, s.sigma.z};
    const std::array<double, 3> colour = {s.colour.x, s.colour.y, s.colour.z};
    for (int i = 0; i < 3; ++i) {
        cloud.positions.push_back(static_cast<float>(position[i]));
        cloud.log_scales.push_back(static_cast<float>(log_positive(sigma[i])));
    }
    for (double q : {s.rotation.w, s.rotation.x, s.rotation.y, s.rotation.z})
        cloud.rotations.push_back(static_cast<float>(q));
    cloud.opacity_logits.push_back(static_cast<float>(logit(s.opacity)));
    for (int i = 0; i < 3; ++i) cloud.sh.push_back(static_cast<float>((colour[i] - 0.5) / kShC0));
    for (int coefficient = 1; coefficient < 16; ++coefficient) {
        const int band = coefficient < 4 ? 1 : coefficient < 9 ? 2 : 3;
        for (int channel = 0; channel < 3; ++channel) {
            const double value = kBandAmplitude[band] * rng.normal();
            cloud.sh.push_back(static_cast<float>(value));
        }
    }
}

Vec3 jittered(const Vec3& colour, Random& rng) {
    const double factor = 1.0 + 0.04 * rng.normal();
    return glm::clamp(colour * factor, Vec3(0.0), Vec3(1.0));
}

// ---- The parts of the scene ---------------------------------------------------------------------

// A (p, q) = (2, 3) torus knot, the tube around it, and the disc layout on the tube.
constexpr int kKnotP = 2, kKnotQ = 3;
constexpr double kKnotMajor = 0.55, kKnotMinor = 0.22, kTubeRadius = 0.11;
constexpr int kAlongKnot = 640, kAroundTube = 48;
static_assert(kDemoKnotGaussians == static_cast<size_t>(kAlongKnot) * kAroundTube);

// Covers the knot's tube with flat discs lying in the surface, coloured in a checker of warm and
// cool stripes (24 along the knot, 6 around the tube) that drift in hue along the knot.
void add_knot(GaussianCloud& cloud, Random& rng) {
    const double dt = kTwoPi / kAlongKnot, dphi = kTwoPi / kAroundTube;
    for (int i = 0; i < kAlongKnot; ++i) {
        for (int j = 0; j < kAroundTube; ++j) {
            const double t = (i + rng.uniform()) * dt;
            const double phi = (j + rng.uniform()) * dphi;
            const SinCos pt = sin_cos(kKnotP * t), qt = sin_cos(kKnotQ * t), ph = sin_cos(phi);
            // The centre line and its derivative.
            const double ring = kKnotMajor + kKnotMinor * qt.cos;
            const Vec3 centre(ring * pt.cos, ring * pt.sin, kKnotMinor * qt.sin);
            const Vec3 velocity(-kKnotMinor * kKnotQ * qt.sin * pt.cos - ring * kKnotP * pt.sin,
                                -kKnotMinor * kKnotQ * qt.sin * pt.sin + ring * kKnotP * pt.cos,
                                kKnotMinor * kKnotQ * qt.cos);
            // A frame around the line: the tangent is never vertical (its horizontal speed is at
            // least p (R - r) > 0), so crossing it with +z gives a smooth normal.
            const Vec3 tangent = glm::normalize(velocity);
            const Vec3 side = glm::normalize(glm::cross(tangent, Vec3(0.0, 0.0, 1.0)));
            const Vec3 binormal = glm::cross(tangent, side);
            const Vec3 normal = ph.cos * side + ph.sin * binormal;
            // Disc axes: along the knot, around the tube, and the thin one along the normal.
            const Vec3 around = glm::cross(normal, tangent);

            Splat s;
            s.position = centre + kTubeRadius * normal;
            const double along_spacing = glm::length(velocity) * dt;
            const double around_spacing = kTubeRadius * dphi;
            const double size_jitter = 1.0 + 0.1 * rng.normal();
            s.sigma = Vec3(0.6 * along_spacing, 0.6 * around_spacing,
                           0.1 * std::min(along_spacing, around_spacing)) * size_jitter;
            s.rotation = quaternion_from_axes(tangent, around, normal);
            s.opacity = rng.uniform(0.85, 0.97);
            const double drift = 0.5 + 0.5 * sin_cos(t).sin;
            const bool warm = ((static_cast<int>(t / kTwoPi * 24.0) +
                                static_cast<int>(phi / kTwoPi * 6.0)) & 1) == 0;
            const Vec3 base = warm ? mix(Vec3(0.95, 0.42, 0.30), Vec3(0.98, 0.78, 0.25), drift)
                                   : mix(Vec3(0.10, 0.55, 0.60), Vec3(0.20, 0.25, 0.70), drift);
            s.colour = jittered(base, rng);
            append(cloud, s, rng);
        }
    }
}

// A ground disc below the knot: flat discs on a jittered square grid, in a grey checker, fading
// out towards the rim so that its edge does not look cut off.
constexpr double kGroundZ = -0.5, kGroundRadius = 1.25, kGroundSpacing = 0.025;
constexpr int kGroundHalfCells = 50;  // kGroundHalfCells * kGroundSpacing = kGroundRadius

// Whether grid point (ix, iy) is on the disc. Membership is decided on the grid point, not the
// jittered one, so that the number of ground Gaussians does not depend on the seed.
constexpr bool on_ground(int ix, int iy) {
    const double gx = ix * kGroundSpacing, gy = iy * kGroundSpacing;
    return gx * gx + gy * gy <= kGroundRadius * kGroundRadius;
}

constexpr size_t ground_count() {
    size_t n = 0;
    for (int iy = -kGroundHalfCells; iy <= kGroundHalfCells; ++iy)
        for (int ix = -kGroundHalfCells; ix <= kGroundHalfCells; ++ix) n += on_ground(ix, iy);
    return n;
}
static_assert(kDemoGroundGaussians == ground_count());

void add_ground(GaussianCloud& cloud, Random& rng) {
    for (int iy = -kGroundHalfCells; iy <= kGroundHalfCells; ++iy) {
        for (int ix = -kGroundHalfCells; ix <= kGroundHalfCells; ++ix) {
            if (!on_ground(ix, iy)) continue;
            const double gx = ix * kGroundSpacing, gy = iy * kGroundSpacing;
            const double jx = rng.uniform(-0.3, 0.3);
            const double jy = rng.uniform(-0.3, 0.3);

            Splat s;
            s.position = Vec3(gx + jx * kGroundSpacing, gy + jy * kGroundSpacing, kGroundZ);
            const double size_jitter = 1.0 + 0.1 * rng.normal();
            s.sigma = Vec3(0.65 * kGroundSpacing, 0.65 * kGroundSpacing, 0.002) * size_jitter;
            s.rotation = {1.0, 0.0, 0.0, 0.0};
            const double r = std::sqrt(gx * gx + gy * gy);
            const double rim = std::clamp((r - 1.0) / (kGroundRadius - 1.0), 0.0, 1.0);
            s.opacity = 0.9 - 0.55 * rim;
            const bool light = ((static_cast<int>(std::floor(gx / 0.25)) +
                                 static_cast<int>(std::floor(gy / 0.25))) & 1) == 0;
            s.colour = jittered(light ? Vec3(0.78, 0.77, 0.74) : Vec3(0.42, 0.42, 0.45), rng);
            append(cloud, s, rng);
        }
    }
}

// Floaters: large, faint, randomly oriented blobs in a ring around the knot (never touching it),
// like the haze a trainer leaves in empty space. Pruning should remove them first.
void add_floaters(GaussianCloud& cloud, Random& rng) {
    for (size_t i = 0; i < kDemoFloaters; ++i) {
        const double distance = rng.uniform(0.95, 1.3);
        const SinCos azimuth = sin_cos(rng.uniform(0.0, kTwoPi));
        const double z = rng.uniform(-0.3, 0.6);
        const double size = rng.uniform(0.05, 0.12);
        Vec3 sigma;
        for (int axis = 0; axis < 3; ++axis) sigma[axis] = size * rng.uniform(0.6, 1.4);
        // A uniformly random rotation: a normalised 4-D Gaussian vector.
        std::array<double, 4> q{};
        double norm = 0.0;
        while (norm < 1e-3) {
            for (double& c : q) c = rng.normal();
            norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        }

        Splat s;
        s.position = Vec3(distance * azimuth.cos, distance * azimuth.sin, z);
        s.sigma = sigma;
        s.rotation = {q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm};
        s.opacity = rng.uniform(0.05, 0.25);
        s.colour = jittered(Vec3(0.70, 0.74, 0.80), rng);
        append(cloud, s, rng);
    }
}

}  // namespace

GaussianCloud make_demo_scene(uint32_t seed) {
    Random rng(seed);
    GaussianCloud cloud;
    cloud.sh_degree = 3;
    const size_t total = kDemoKnotGaussians + kDemoGroundGaussians + kDemoFloaters;
    cloud.positions.reserve(3 * total);
    cloud.log_scales.reserve(3 * total);
    cloud.rotations.reserve(4 * total);
    cloud.opacity_logits.reserve(total);
    cloud.sh.reserve(3 * 16 * total);
    add_knot(cloud, rng);
    add_ground(cloud, rng);
    add_floaters(cloud, rng);
    return cloud;
}

std::vector<Camera> make_orbit_cameras(int count, int width, int height, double radius,
                                       double elevation_deg) {
    if (count < 1 || width < 1 || height < 1)
        throw std::invalid_argument("make_orbit_cameras: count " + std::to_string(count) +
                                    " and size " + std::to_string(width) + " x " +
                                    std::to_string(height) + " must be at least 1");
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw std::invalid_argument("make_orbit_cameras: radius " + std::to_string(radius) +
                                    " must be positive and finite");
    if (!(std::abs(elevation_deg) < 90.0))
        throw std::invalid_argument("make_orbit_cameras: elevation " +
                                    std::to_string(elevation_deg) +
                                    " degrees must be strictly between -90 and 90 (the view "
                                    "direction would be parallel to up)");

    constexpr double kHorizontalFovDeg = 50.0;
    const double focal = 0.5 * width / std::tan(0.5 * kHorizontalFovDeg * kPi / 180.0);
    const double elevation = elevation_deg * kPi / 180.0;
    std::vector<Camera> cameras;
    cameras.reserve(count);
    for (int i = 0; i < count; ++i) {
        const double azimuth = kTwoPi * i / count;
        const Vec3 eye = radius * Vec3(std::cos(elevation) * std::cos(azimuth),
                                       std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
        Camera camera = Camera::look_at(eye, Vec3(0.0), Vec3(0.0, 0.0, 1.0), width, height, focal, focal);
        char name[32];
        std::snprintf(name, sizeof name, "orbit_%03d", i);
        camera.name = name;
        cameras.push_back(std::move(camera));
    }
    return cameras;
}

}  // namespace vksplat
