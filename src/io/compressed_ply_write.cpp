// Writes PlayCanvas's compressed PLY as splat-transform does (and read_compressed_ply reads it):
// splats in Morton order, so that each chunk of 256 covers a small box and its ranges quantise
// finely; per chunk the ranges of position, log scale and colour as floats; per splat four words
// packing its values relative to those ranges; the higher SH as bytes.
#include <algorithm>
#include <cmath>

#include "io/compressed_ply_layout.hpp"
#include "io/formats_detail.hpp"
#include "io/morton_order.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

using namespace compressed_ply;
// splat-transform clamps the log-scale ranges here: some trained scenes hold infinite scales.
constexpr float kLargestLogScale = 20.0f;
// The SH bytes span [-4, 4].
constexpr double kShSpan = 8.0;

struct Range {
    float min = INFINITY, max = -INFINITY;
    void add(float v) {
        min = std::min(min, v);
        max = std::max(max, v);
    }
    // Where `v` lies in the range, 0 to 1; a range too small to divide by gives 0.
    double where(double v) const {
        if (v <= min) return 0;
        if (v >= max) return 1;
        return double(max) - min < 1e-5 ? 0 : (v - min) / (double(max) - min);
    }
};

uint32_t unorm(double t, int bits) {
    const double steps = double((1u << bits) - 1);
    if (!(t == t)) return 0;  // NaN
    return static_cast<uint32_t>(std::clamp(std::floor(t * steps + 0.5), 0.0, steps));
}

uint32_t pack_11_10_11(double x, double y, double z) { return unorm(x, 11) << 21 | unorm(y, 10) << 11 | unorm(z, 11); }

// Smallest three, in rot_0..rot_3 (w, x, y, z) order: the index of the largest component in the top
// two bits, each other one in 10 bits as q * sqrt(1/2) + 1/2 (their magnitudes are below sqrt(1/2)).
uint32_t pack_rotation(const float* rotation) {
    double q[4], norm = 0;
    for (size_t a = 0; a < 4; ++a) norm += double(rotation[a]) * rotation[a];
    norm = std::sqrt(norm);
    for (size_t a = 0; a < 4; ++a) q[a] = norm > 0 && std::isfinite(norm) ? rotation[a] / norm : (a == 0 ? 1.0 : 0.0);
    uint32_t largest = 0;
    for (uint32_t a = 1; a < 4; ++a)
        if (std::abs(q[a]) > std::abs(q[largest])) largest = a;
    const double sign = q[largest] < 0 ? -1 : 1;  // q and -q are the same rotation: the largest is kept positive
    uint32_t packed = largest;
    for (uint32_t a = 0; a < 4; ++a)
        if (a != largest) packed = packed << 10 | unorm(sign * q[a] * std::sqrt(0.5) + 0.5, 10);
    return packed;
}

uint8_t sh_byte(double value) {
    const double byte = std::trunc((value / kShSpan + 0.5) * 256);
    return byte == byte ? static_cast<uint8_t>(std::clamp(byte, 0.0, 255.0)) : 128;
}

std::string header_text(size_t count, size_t chunks, size_t sh_rest) {
    std::string text = "ply\nformat binary_little_endian 1.0\ncomment written by vksplat\nelement chunk " +
                       std::to_string(chunks) + "\n";
    for (const char* name : kChunkGeometryFields) text += std::string("property float ") + name + "\n";
    for (const char* name : kChunkColourFields) text += std::string("property float ") + name + "\n";
    text += "element vertex " + std::to_string(count) + "\n";
    for (const char* name : kVertexFields) text += std::string("property uint ") + name + "\n";
    if (sh_rest) {
        text += "element sh " + std::to_string(count) + "\n";
        for (size_t r = 0; r < sh_rest; ++r) text += "property uchar f_rest_" + std::to_string(r) + "\n";
    }
    return text + "end_header\n";
}

}  // namespace

void write_compressed_ply(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode) {
    const std::string where = path.string();
    detail::check_writable(cloud, where);
    for (size_t i = 0; i < cloud.positions.size(); ++i)
        if (!std::isfinite(cloud.positions[i]))
            throw InputError(where, "cannot write Gaussian " + std::to_string(i / 3) +
                                        ": its position is not finite (sanitize() the cloud first)");
    const size_t n = cloud.size();
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    const size_t rest_per_channel = coefficients - 1;
    const size_t chunks = (n + kChunkSize - 1) / kChunkSize;
    const std::vector<size_t> order = detail::morton_order(cloud);
    const auto colour = [&](size_t i, size_t a) {
        return static_cast<float>(cloud.sh[i * coefficients * 3 + a] * detail::kShC0 + 0.5);
    };

    std::string chunk_rows, vertex_rows, sh_rows;
    chunk_rows.reserve(chunks * (std::size(kChunkGeometryFields) + std::size(kChunkColourFields)) * 4);
    vertex_rows.reserve(n * 16);
    sh_rows.reserve(n * rest_per_channel * 3);
    for (size_t c = 0; c < chunks; ++c) {
        const size_t first = c * kChunkSize, last = std::min(n, first + kChunkSize);
        Range position[3], scale[3], rgb[3];
        for (size_t s = first; s < last; ++s)
            for (size_t a = 0; a < 3; ++a) {
                position[a].add(cloud.positions[order[s] * 3 + a]);
                scale[a].add(cloud.log_scales[order[s] * 3 + a]);
                rgb[a].add(colour(order[s], a));
            }
        for (Range& range : scale) {
            range.min = std::clamp(range.min, -kLargestLogScale, kLargestLogScale);
            range.max = std::clamp(range.max, -kLargestLogScale, kLargestLogScale);
        }
        for (const Range* ranges : {position, scale, rgb}) {
            for (size_t a = 0; a < 3; ++a) detail::store_little_endian(chunk_rows, ranges[a].min);
            for (size_t a = 0; a < 3; ++a) detail::store_little_endian(chunk_rows, ranges[a].max);
        }
        for (size_t s = first; s < last; ++s) {
            const size_t i = order[s];
            const float* p = &cloud.positions[i * 3];
            const float* l = &cloud.log_scales[i * 3];
            detail::store_little_endian(
                vertex_rows, pack_11_10_11(position[0].where(p[0]), position[1].where(p[1]), position[2].where(p[2])));
            detail::store_little_endian(vertex_rows, pack_rotation(&cloud.rotations[i * 4]));
            detail::store_little_endian(vertex_rows,
                                        pack_11_10_11(scale[0].where(l[0]), scale[1].where(l[1]), scale[2].where(l[2])));
            detail::store_little_endian(vertex_rows, unorm(rgb[0].where(colour(i, 0)), 8) << 24 |
                                                         unorm(rgb[1].where(colour(i, 1)), 8) << 16 |
                                                         unorm(rgb[2].where(colour(i, 2)), 8) << 8 |
                                                         unorm(detail::sigmoid(cloud.opacity_logits[i]), 8));
            // f_rest_* channel-major, as in the INRIA layout; the cloud keeps [coefficient][rgb].
            for (size_t channel = 0; channel < 3; ++channel)
                for (size_t k = 1; k < coefficients; ++k)
                    sh_rows += static_cast<char>(sh_byte(cloud.sh[i * coefficients * 3 + k * 3 + channel]));
        }
    }
    std::string header = header_text(n, chunks, rest_per_channel * 3);
    write_file_atomically(path, mode, [&](std::ostream& out) {
        for (const std::string* part : {&header, &chunk_rows, &vertex_rows, &sh_rows})
            out.write(part->data(), static_cast<std::streamsize>(part->size()));
    });
}

}  // namespace vksplat::io
