// Niantic's SPZ: a gzip stream holding a 16-byte header and then each attribute of every splat in
// turn (positions, alphas, colours, scales, rotations, SH), quantised to bytes.
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

constexpr uint32_t kMagic = 0x5053474e;  // "NGSP" little-endian
constexpr size_t kHeaderBytes = 16;
constexpr uint8_t kFlagAntialiased = 0x1;
constexpr uint8_t kFlagHasExtensions = 0x2;
// SPZ scales the DC colour by this instead of SH_C0, so that colours a little outside [0, 1] fit.
constexpr double kColourScale = 0.15;
constexpr double kSqrtHalf = 0.70710678118654752440;
constexpr uint32_t kNineBits = (1u << 9) - 1;
constexpr int kDefaultFractionalBits = 12;
constexpr int32_t kMaxFixed24 = (1 << 23) - 1;

// SPZ stores its splats in RUB axes (x right, y up, z back: OpenGL, three.js); PLY files and the
// cloud use RDF (x right, y down, z forward: OpenCV, COLMAP). The change is a half turn about x,
// its own inverse: y and z change sign, and so do the quaternion's y and z and every SH
// coefficient whose basis function is odd in y and z together (Niantic's reference and
// splat-transform convert the same way).
constexpr float kFlipPosition[3] = {1, -1, -1};
constexpr float kFlipRotation[4] = {1, 1, -1, -1};  // w, x, y, z
constexpr float kFlipSh[15] = {-1, -1, 1,                  // degree 1: y, z, x
                               -1, 1, 1, -1, 1,            // degree 2: xy, yz, 3z^2-1, xz, x^2-y^2
                               -1, 1, -1, -1, 1, -1, 1};   // degree 3

struct Layout {
    uint64_t positions = 0, alphas = 0, colours = 0, scales = 0, rotations = 0, sh = 0, end = 0;
};

// Byte offsets of each attribute block for n splats.
Layout layout_for(uint64_t n, uint32_t version, int sh_rest) {
    Layout layout;
    layout.positions = 0;
    layout.alphas = layout.positions + n * 9;
    layout.colours = layout.alphas + n;
    layout.scales = layout.colours + n * 3;
    layout.rotations = layout.scales + n * 3;
    layout.sh = layout.rotations + n * (version >= 3 ? 4 : 3);
    layout.end = layout.sh + n * static_cast<uint64_t>(sh_rest) * 3;
    return layout;
}

// Quaternion (x, y, z, w), unit length, from the 3-byte form of version 2 (w >= 0 implied).
std::array<double, 4> unpack_first_three(const uint8_t* bytes) {
    std::array<double, 4> q{};
    double sum = 0;
    for (size_t a = 0; a < 3; ++a) {
        q[a] = bytes[a] / 127.5 - 1.0;
        sum += q[a] * q[a];
    }
    q[3] = std::sqrt(std::max(0.0, 1.0 - sum));
    return q;
}

// Quaternion (x, y, z, w) from the "smallest three" form of version 3: the index of the largest
// component in the top two bits, then the other three (in order, first in the highest bits) as a
// sign bit and a 9-bit magnitude in units of sqrt(1/2) / 511.
std::array<double, 4> unpack_smallest_three(uint32_t packed) {
    std::array<double, 4> q{};
    const uint32_t largest = packed >> 30;
    double sum = 0;
    for (int a = 3; a >= 0; --a) {
        if (static_cast<uint32_t>(a) == largest) continue;
        const uint32_t magnitude = packed & kNineBits;
        const bool negative = (packed >> 9) & 1u;
        packed >>= 10;
        q[a] = kSqrtHalf * magnitude / kNineBits * (negative ? -1.0 : 1.0);
        sum += q[a] * q[a];
    }
    q[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
    return q;
}

uint32_t pack_smallest_three(std::array<double, 4> q) {
    double norm = 0;
    for (double v : q) norm += v * v;
    norm = std::sqrt(norm);
    if (!(norm > 0) || !std::isfinite(norm)) {
        q = {0, 0, 0, 1};
        norm = 1;
    }
    for (double& v : q) v /= norm;
    uint32_t largest = 0;
    for (uint32_t a = 1; a < 4; ++a)
        if (std::abs(q[a]) > std::abs(q[largest])) largest = a;
    const bool negate = q[largest] < 0;  // q and -q are the same rotation: make the largest positive
    uint32_t packed = largest;
    for (uint32_t a = 0; a < 4; ++a) {
        if (a == largest) continue;
        const uint32_t negative = (q[a] < 0) != negate ? 1u : 0u;
        const uint32_t magnitude =
            std::min(kNineBits, static_cast<uint32_t>(kNineBits * (std::abs(q[a]) / kSqrtHalf) + 0.5));
        packed = (packed << 10) | (negative << 9) | magnitude;
    }
    return packed;
}

std::string hex(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08x", value);
    return text;
}

}  // namespace

GaussianCloud read_spz(const std::filesystem::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    const std::string file = detail::read_file_bytes(path, where);

    // SPZ is gzip; an uncompressed stream (starting with the SPZ magic) is accepted as well.
    std::string data;
    std::unique_ptr<detail::Inflater> inflater;
    const bool gzipped = file.size() >= 2 && static_cast<uint8_t>(file[0]) == 0x1f && static_cast<uint8_t>(file[1]) == 0x8b;
    if (gzipped) {
        inflater = std::make_unique<detail::Inflater>(file, detail::Inflater::Wrapping::gzip, where);
        inflater->read(data, kHeaderBytes);
    } else if (file.size() >= 4 && detail::load_little_endian<uint32_t>(file.data()) == kMagic) {
        data = file;
    } else if (file.size() < 4) {
        throw InputError(where, "truncated: " + std::to_string(file.size()) + " bytes are too few for an SPZ file");
    } else {
        throw InputError(where, "not an SPZ file: wrong magic (neither gzip 1f 8b nor SPZ 'NGSP' "
                                "0x5053474e; the file starts with " +
                                    hex(detail::load_little_endian<uint32_t>(file.data())) + ")");
    }
    if (data.size() < kHeaderBytes)
        throw InputError(where, "truncated: the SPZ header needs 16 bytes but the data ends after " +
                                    std::to_string(data.size()));

    const uint32_t magic = detail::load_little_endian<uint32_t>(data.data());
    const uint32_t version = detail::load_little_endian<uint32_t>(data.data() + 4);
    const uint32_t count = detail::load_little_endian<uint32_t>(data.data() + 8);
    const auto sh_degree = static_cast<uint8_t>(data[12]);
    const auto fractional_bits = static_cast<uint8_t>(data[13]);
    const auto flags = static_cast<uint8_t>(data[14]);
    if (magic != kMagic)
        throw InputError(where, "not an SPZ file: wrong magic " + hex(magic) + " in the decompressed header (expected " +
                                    hex(kMagic) + ", 'NGSP')");
    if (version != 2 && version != 3)
        throw InputError(where, "unsupported SPZ version " + std::to_string(version) + " (versions 2 and 3 are supported)");
    if (sh_degree > 3)
        throw InputError(where, "unsupported SH degree " + std::to_string(sh_degree) + " (0 to 3 are supported)");
    if (flags & kFlagHasExtensions)
        throw InputError(where, "uses SPZ extensions (flag 0x2), which this reader does not support");
    if (fractional_bits > 24)
        throw InputError(where, "has " + std::to_string(fractional_bits) +
                                    " fractional bits for 24-bit positions (at most 24 make sense)");

    const int sh_rest = sh_coefficients_for_degree(sh_degree) - 1;
    const Layout layout = layout_for(count, version, sh_rest);
    if (gzipped) inflater->read(data, layout.end);
    const uint64_t payload = data.size() - kHeaderBytes;
    const std::string expectation = "the header says " + std::to_string(count) + " splats of SH degree " +
                                    std::to_string(sh_degree) + " (" + std::to_string(layout.end) +
                                    " bytes after the header)";
    if (payload < layout.end)
        throw InputError(where, "truncated: " + expectation + " but the " + (gzipped ? "decompressed " : "") +
                                    "data holds only " + std::to_string(payload));
    if ((gzipped && !inflater->at_end()) || payload > layout.end)
        throw InputError(where, "size does not match the header: " + expectation + " but more data follows");

    const auto* body = reinterpret_cast<const uint8_t*>(data.data() + kHeaderBytes);
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(count);
    const size_t coefficients = static_cast<size_t>(sh_rest + 1);
    for (size_t i = 0; i < count; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const uint8_t* p = body + layout.positions + i * 9 + a * 3;
            int32_t fixed = static_cast<int32_t>(p[0] | (p[1] << 8) | (p[2] << 16));
            if (fixed & 0x800000) fixed -= 0x1000000;  // sign extension
            cloud.positions[i * 3 + a] =
                kFlipPosition[a] * static_cast<float>(std::ldexp(static_cast<double>(fixed), -fractional_bits));
            cloud.log_scales[i * 3 + a] = static_cast<float>(body[layout.scales + i * 3 + a] / 16.0 - 10.0);
            cloud.sh[i * coefficients * 3 + a] =
                static_cast<float>((body[layout.colours + i * 3 + a] / 255.0 - 0.5) / kColourScale);
        }
        cloud.opacity_logits[i] = detail::logit_of(body[layout.alphas + i] / 255.0);
        const std::array<double, 4> q =
            version >= 3 ? unpack_smallest_three(detail::load_little_endian<uint32_t>(
                               reinterpret_cast<const char*>(body + layout.rotations + i * 4)))
                         : unpack_first_three(body + layout.rotations + i * 3);
        cloud.rotations[i * 4 + 0] = static_cast<float>(q[3]);  // SPZ is x, y, z, w; the cloud w, x, y, z
        for (size_t a = 0; a < 3; ++a) cloud.rotations[i * 4 + 1 + a] = kFlipRotation[1 + a] * static_cast<float>(q[a]);
        // SPZ's SH are [coefficient][rgb] without the DC term, like the cloud's after it.
        const uint8_t* sh = body + layout.sh + i * static_cast<size_t>(sh_rest) * 3;
        for (size_t k = 0; k < static_cast<size_t>(sh_rest) * 3; ++k)
            cloud.sh[i * coefficients * 3 + 3 + k] = kFlipSh[k / 3] * static_cast<float>((sh[k] - 128.0) / 128.0);
    }
    if (notes && (flags & kFlagAntialiased))
        notes->push_back(where + ": flagged antialiased (trained with an anti-aliasing filter); it is rendered "
                                 "without one");
    return cloud;
}

void write_spz(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode) {
    const std::string where = path.string();
    detail::check_writable(cloud, where);
    if (cloud.size() > UINT32_MAX)
        throw InputError(where, "cannot write " + std::to_string(cloud.size()) + " splats (SPZ holds at most 2^32 - 1)");

    double largest = 0;
    for (size_t i = 0; i < cloud.positions.size(); ++i) {
        const double v = cloud.positions[i];
        if (!std::isfinite(v))
            throw InputError(where, "cannot write Gaussian " + std::to_string(i / 3) +
                                        ": its position is not finite (sanitize() the cloud first)");
        largest = std::max(largest, std::abs(v));
    }
    int fractional_bits = kDefaultFractionalBits;
    while (fractional_bits > 0 && std::round(std::ldexp(largest, fractional_bits)) > kMaxFixed24) --fractional_bits;
    if (std::round(largest) > kMaxFixed24)
        throw InputError(where, "cannot write a coordinate of magnitude " + std::to_string(largest) +
                                    ": SPZ positions are 24-bit fixed point (at most 2^23 - 1)");

    const size_t n = cloud.size();
    const int sh_rest = cloud.sh_coefficients() - 1;
    const size_t coefficients = static_cast<size_t>(sh_rest + 1);
    constexpr uint32_t kVersion = 3;
    const Layout layout = layout_for(n, kVersion, sh_rest);
    std::string data;
    data.reserve(kHeaderBytes + layout.end);
    detail::store_little_endian(data, kMagic);
    detail::store_little_endian(data, kVersion);
    detail::store_little_endian(data, static_cast<uint32_t>(n));
    data += static_cast<char>(cloud.sh_degree);
    data += static_cast<char>(fractional_bits);
    data += '\0';  // flags: not antialiased, no extensions
    data += '\0';  // reserved
    data.resize(kHeaderBytes + layout.end, '\0');
    auto* body = reinterpret_cast<uint8_t*>(data.data() + kHeaderBytes);
    for (size_t i = 0; i < n; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const auto fixed = static_cast<int32_t>(
                std::round(std::ldexp(double(kFlipPosition[a] * cloud.positions[i * 3 + a]), fractional_bits)));
            uint8_t* p = body + layout.positions + i * 9 + a * 3;
            p[0] = static_cast<uint8_t>(fixed & 0xff);
            p[1] = static_cast<uint8_t>((fixed >> 8) & 0xff);
            p[2] = static_cast<uint8_t>((fixed >> 16) & 0xff);
            body[layout.scales + i * 3 + a] = detail::to_byte((cloud.log_scales[i * 3 + a] + 10.0) * 16.0);
            body[layout.colours + i * 3 + a] =
                detail::to_byte(cloud.sh[i * coefficients * 3 + a] * (kColourScale * 255.0) + 0.5 * 255.0);
        }
        body[layout.alphas + i] = detail::to_byte(detail::sigmoid(cloud.opacity_logits[i]) * 255.0);
        const float* r = cloud.rotations.data() + i * 4;
        const uint32_t packed = pack_smallest_three(
            {kFlipRotation[1] * r[1], kFlipRotation[2] * r[2], kFlipRotation[3] * r[3], r[0]});
        for (size_t b = 0; b < 4; ++b) body[layout.rotations + i * 4 + b] = static_cast<uint8_t>(packed >> (8 * b));
        uint8_t* sh = body + layout.sh + i * static_cast<size_t>(sh_rest) * 3;
        for (size_t k = 0; k < static_cast<size_t>(sh_rest) * 3; ++k)
            sh[k] = detail::to_byte(kFlipSh[k / 3] * cloud.sh[i * coefficients * 3 + 3 + k] * 128.0 + 128.0);
    }
    const std::string compressed = detail::deflate_bytes(data, detail::Inflater::Wrapping::gzip, where);
    write_file_atomically(path, mode, [&](std::ostream& out) {
        out.write(compressed.data(), static_cast<std::streamsize>(compressed.size()));
    });
}

}  // namespace vksplat::io
