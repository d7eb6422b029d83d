// The antimatter15 .splat layout: a bare array of 32-byte records, the format of the first web viewers.
#include <array>
#include <cmath>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

constexpr size_t kRecordBytes = 32;

}  // namespace

GaussianCloud read_splat(const std::filesystem::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    const std::string bytes = detail::read_file_bytes(path, where);
    if (bytes.size() % kRecordBytes != 0)
        throw InputError(where, "truncated or not a .splat file: its size, " + std::to_string(bytes.size()) +
                                    " bytes, is not a multiple of the 32-byte record (the last record has " +
                                    std::to_string(bytes.size() % kRecordBytes) + " bytes)");
    const size_t count = bytes.size() / kRecordBytes;

    GaussianCloud cloud;
    cloud.sh_degree = 0;
    cloud.resize(count);
    size_t degenerate_rotations = 0;
    for (size_t i = 0; i < count; ++i) {
        const char* record = bytes.data() + i * kRecordBytes;
        const auto* u8 = reinterpret_cast<const uint8_t*>(record + 24);
        for (size_t a = 0; a < 3; ++a) {
            cloud.positions[i * 3 + a] = detail::load_little_endian<float>(record + 4 * a);
            const float scale = detail::load_little_endian<float>(record + 12 + 4 * a);
            cloud.log_scales[i * 3 + a] = std::log(scale);
            cloud.sh[i * 3 + a] = static_cast<float>((u8[a] / 255.0 - 0.5) / detail::kShC0);
        }
        cloud.opacity_logits[i] = detail::logit_of(u8[3] / 255.0);
        std::array<double, 4> q{};
        double norm = 0;
        for (size_t a = 0; a < 4; ++a) {
            q[a] = (u8[4 + a] - 128.0) / 128.0;
            norm += q[a] * q[a];
        }
        norm = std::sqrt(norm);
        if (norm == 0) {
            ++degenerate_rotations;
            q = {1, 0, 0, 0};
            norm = 1;
        }
        for (size_t a = 0; a < 4; ++a) cloud.rotations[i * 4 + a] = static_cast<float>(q[a] / norm);
    }
    if (notes && degenerate_rotations)
        notes->push_back(where + ": " + std::to_string(degenerate_rotations) +
                         " splats had an all-zero quaternion; they were given the identity rotation");
    return cloud;
}

void write_splat(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode) {
    const std::string where = path.string();
    detail::check_writable(cloud, where);
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    write_file_atomically(path, mode, [&](std::ostream& out) {
        constexpr size_t kBatch = 16384;
        std::string block;
        block.reserve(kBatch * kRecordBytes);
        for (size_t first = 0; first < cloud.size(); first += kBatch) {
            block.clear();
            for (size_t i = first; i < std::min(first + kBatch, cloud.size()); ++i) {
                for (size_t a = 0; a < 3; ++a) detail::store_little_endian(block, cloud.positions[i * 3 + a]);
                for (size_t a = 0; a < 3; ++a)
                    detail::store_little_endian(block, std::exp(cloud.log_scales[i * 3 + a]));
                for (size_t a = 0; a < 3; ++a)
                    block += static_cast<char>(
                        detail::to_byte((0.5 + detail::kShC0 * cloud.sh[i * coefficients * 3 + a]) * 255.0));
                block += static_cast<char>(detail::to_byte(detail::sigmoid(cloud.opacity_logits[i]) * 255.0));
                std::array<double, 4> q{};
                double norm = 0;
                for (size_t a = 0; a < 4; ++a) {
                    q[a] = cloud.rotations[i * 4 + a];
                    norm += q[a] * q[a];
                }
                norm = std::sqrt(norm);
                if (!(norm > 0) || !std::isfinite(norm)) {
                    q = {1, 0, 0, 0};
                    norm = 1;
                }
                for (size_t a = 0; a < 4; ++a) block += static_cast<char>(detail::to_byte(q[a] / norm * 128.0 + 128.0));
            }
            out.write(block.data(), static_cast<std::streamsize>(block.size()));
        }
    });
}

}  // namespace vksplat::io
