// Writes PlayCanvas SOG (io/sog_layout.hpp) as splat-transform does: splats in Morton order (so
// that neighbouring texels hold neighbouring, alike splats and WebP compresses them well),
// positions and rotations packed per splat, scales and colours as indices into 256-entry
// codebooks, the higher SH as a palette found by k-means whose values are indices into a codebook
// of their own.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "io/codebook.hpp"
#include "io/formats_detail.hpp"
#include "io/morton_order.hpp"
#include "io/sog_layout.hpp"
#include "io/webp_image.hpp"
#include "io/zip_archive.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/version.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;
using detail::RgbaImage;
using nlohmann::ordered_json;

// The SH palette: splat-transform fits up to 64Ki entries (half to all of the splats) on a GPU;
// on a CPU, k-means costs splats x entries x 45 per step. 4096 entries, fitted to at most 16
// splats an entry (every splat of snowmiku's 57,694) in 5 steps from k-means++ seeds, then every
// splat labelled with its nearest entry: 38 s of CPU time for snowmiku. Fitted to 8 splats an
// entry, the palette's error grew by a fifth (mean squared 0.063 against 0.052) in 40% of the time.
constexpr size_t kPaletteEntries = 4096;
constexpr size_t kPaletteFitRowsPerEntry = 16;
constexpr int kPaletteIterations = 5;

RgbaImage blank_image(int width, int height) {
    RgbaImage image{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 0)};
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

// SOG's encodings are of finite values only (k-means and the position range would turn one
// infinity or NaN into garbage for every splat), and a quaternion of length 0 has no unit one.
void refuse_undefined(const GaussianCloud& cloud, const std::string& where) {
    const auto refuse = [&](size_t gaussian, const std::string& problem) {
        throw InputError(where, "cannot write Gaussian " + std::to_string(gaussian) + " as SOG: " + problem +
                                    " (sanitize the scene first)");
    };
    const auto check = [&](const std::vector<float>& values, size_t per_splat, const char* what) {
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i])) refuse(i / per_splat, std::string("its ") + what + " is not finite");
    };
    check(cloud.positions, 3, "position");
    check(cloud.log_scales, 3, "scale");
    check(cloud.rotations, 4, "rotation");
    check(cloud.sh, size_t(cloud.sh_coefficients()) * 3, "colour (SH)");
    for (size_t i = 0; i < cloud.size(); ++i)
        if (std::all_of(&cloud.rotations[i * 4], &cloud.rotations[i * 4 + 4], [](float v) { return v == 0.0f; }))
            refuse(i, "its rotation is a quaternion of length 0");
}

struct SogFiles {
    ordered_json meta;
    std::vector<std::pair<std::string, std::string>> textures;  // name, WebP bytes
};

class SogEncoder {
public:
    SogEncoder(const GaussianCloud& cloud, std::string where)
        : cloud_(cloud), where_(std::move(where)), order_(detail::morton_order(cloud)),
          size_(detail::sog::texture_size(cloud.size())) {}

    SogFiles encode() {
        files_.meta = {{"version", detail::sog::kVersion},
                       {"asset", {{"generator", std::string("vksplat ") + kVersion}}},
                       {"count", cloud_.size()}};
        encode_means();
        encode_scales();
        encode_quaternions();
        encode_colours();
        if (cloud_.sh_degree > 0) encode_sh_rest();
        return std::move(files_);
    }

private:
    void add_texture(const char* name, const RgbaImage& image) {
        files_.textures.emplace_back(name, detail::encode_lossless_webp(image, where_ + ": " + name));
    }

    // x, y, z of splat `order_[i]` at texel i, 16 bits split over two textures.
    void encode_means() {
        std::vector<double> low(3, 0.0), high(3, 0.0);
        for (size_t a = 0; a < 3 && !cloud_.empty(); ++a) {
            low[a] = high[a] = detail::sog::log_encode(cloud_.positions[a]);
            for (size_t i = 0; i < cloud_.size(); ++i) {
                const double v = detail::sog::log_encode(cloud_.positions[i * 3 + a]);
                low[a] = std::min(low[a], v);
                high[a] = std::max(high[a], v);
            }
        }
        RgbaImage lower = blank_image(size_.width, size_.height), upper = lower;
        for (size_t i = 0; i < order_.size(); ++i)
            for (size_t a = 0; a < 3; ++a) {
                const double v = detail::sog::log_encode(cloud_.positions[order_[i] * 3 + a]);
                const double t = high[a] > low[a] ? (v - low[a]) / (high[a] - low[a]) : 0.0;
                const auto q = static_cast<uint32_t>(std::clamp(std::round(t * 65535.0), 0.0, 65535.0));
                lower.rgba[i * 4 + a] = static_cast<uint8_t>(q & 0xff);
                upper.rgba[i * 4 + a] = static_cast<uint8_t>(q >> 8);
            }
        add_texture("means_l.webp", lower);
        add_texture("means_u.webp", upper);
        files_.meta["means"] = {{"mins", low}, {"maxs", high}, {"files", {"means_l.webp", "means_u.webp"}}};
    }

    // The three largest-but-one components of the unit quaternion, times sqrt(2), as bytes.
    void encode_quaternions() {
        RgbaImage image = blank_image(size_.width, size_.height);
        for (size_t i = 0; i < order_.size(); ++i) {
            const float* raw = &cloud_.rotations[order_[i] * 4];
            double q[4] = {raw[0], raw[1], raw[2], raw[3]};
            const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            for (double& v : q) v /= length;
            int largest = 0;
            for (int k = 1; k < 4; ++k)
                if (std::abs(q[k]) > std::abs(q[largest])) largest = k;
            const double sign = q[largest] < 0 ? -1.0 : 1.0;
            for (int k = 0, slot = 0; k < 4; ++k)
                if (k != largest)
                    image.rgba[i * 4 + slot++] = detail::to_byte(255.0 * (sign * q[k] * detail::sog::kSqrt2 + 1.0) / 2.0);
            image.rgba[i * 4 + 3] = static_cast<uint8_t>(detail::sog::kQuaternionTagBase + largest);
        }
        add_texture("quats.webp", image);
        files_.meta["quats"] = {{"files", {"quats.webp"}}};
    }

    // Three values a splat from `values` (3 a splat, `stride` apart) as indices into one codebook,
    // in the texture's r, g, b; alpha from `alpha` (255 when it is null).
    ordered_json encode_codebook_texture(const char* name, const std::vector<float>& values, size_t stride,
                                         const std::vector<uint8_t>* alpha) {
        std::vector<float> pooled(cloud_.size() * 3);
        for (size_t i = 0; i < cloud_.size(); ++i)
            for (size_t c = 0; c < 3; ++c) pooled[i * 3 + c] = values[i * stride + c];
        const detail::ScalarCodebook book = detail::scalar_codebook(pooled, detail::sog::kCodebookSize);
        RgbaImage image = blank_image(size_.width, size_.height);
        for (size_t i = 0; i < order_.size(); ++i) {
            for (size_t c = 0; c < 3; ++c) image.rgba[i * 4 + c] = book.labels[order_[i] * 3 + c];
            if (alpha) image.rgba[i * 4 + 3] = (*alpha)[order_[i]];
        }
        add_texture(name, image);
        return {{"codebook", book.values}, {"files", {name}}};
    }

    void encode_scales() {
        files_.meta["scales"] = encode_codebook_texture("scales.webp", cloud_.log_scales, 3, nullptr);
    }

    void encode_colours() {
        std::vector<uint8_t> opacity(cloud_.size());
        for (size_t i = 0; i < cloud_.size(); ++i)
            opacity[i] = detail::to_byte(detail::sigmoid(cloud_.opacity_logits[i]) * 255.0);
        files_.meta["sh0"] =
            encode_codebook_texture("sh0.webp", cloud_.sh, size_t(cloud_.sh_coefficients()) * 3, &opacity);
    }

    void encode_sh_rest() {
        const int coefficients = detail::sog::rest_coefficients(cloud_.sh_degree);
        const size_t dims = size_t(coefficients) * 3, stride = size_t(cloud_.sh_coefficients()) * 3;
        std::vector<float> rest(cloud_.size() * dims);
        for (size_t i = 0; i < cloud_.size(); ++i)
            std::copy_n(&cloud_.sh[i * stride + 3], dims, &rest[i * dims]);
        const detail::Palette palette = detail::vector_palette(
            rest, dims, kPaletteEntries, kPaletteEntries * kPaletteFitRowsPerEntry, kPaletteIterations);
        const detail::ScalarCodebook book = detail::scalar_codebook(palette.centroids, detail::sog::kCodebookSize);

        const int per_row = detail::sog::kPaletteEntriesPerRow;
        const int rows = std::max<int>(1, static_cast<int>((palette.entries() + per_row - 1) / per_row));
        RgbaImage centroids = blank_image(per_row * coefficients, rows);
        for (size_t e = 0; e < palette.entries(); ++e)
            for (int j = 0; j < coefficients; ++j) {
                const size_t texel = (e / per_row) * size_t(per_row * coefficients) + (e % per_row) * coefficients + j;
                for (size_t c = 0; c < 3; ++c) centroids.rgba[texel * 4 + c] = book.labels[e * dims + j * 3 + c];
            }
        RgbaImage labels = blank_image(size_.width, size_.height);
        for (size_t i = 0; i < order_.size(); ++i) {
            const uint32_t label = palette.labels[order_[i]];
            labels.rgba[i * 4 + 0] = static_cast<uint8_t>(label & 0xff);
            labels.rgba[i * 4 + 1] = static_cast<uint8_t>(label >> 8);
        }
        add_texture("shN_centroids.webp", centroids);
        add_texture("shN_labels.webp", labels);
        files_.meta["shN"] = {{"count", palette.entries()},
                              {"bands", cloud_.sh_degree},
                              {"codebook", book.values},
                              {"files", {"shN_centroids.webp", "shN_labels.webp"}}};
    }

    const GaussianCloud& cloud_;
    std::string where_;
    std::vector<size_t> order_;
    detail::sog::TextureSize size_;
    SogFiles files_;
};

void write_bytes(const fs::path& path, WriteMode mode, const std::string& bytes) {
    write_file_atomically(path, mode, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace

void write_sog(const GaussianCloud& cloud, const fs::path& path, WriteMode mode) {
    const std::string where = path.string();
    // Every file is checked before any is written, so a refusal leaves the folder as it was.
    for (const fs::path& file : detail::sog::output_files(path)) check_writable(file, mode);
    detail::check_writable(cloud, where);
    refuse_undefined(cloud, where);
    SogFiles files = SogEncoder(cloud, where).encode();
    const std::string meta = files.meta.dump();
    if (!detail::sog::is_meta_json(path)) {
        files.textures.insert(files.textures.begin(), {detail::sog::kMetaName, meta});
        return write_bytes(path, mode, zip::stored_archive(files.textures, where));
    }
    // meta.json last: until it is there, the folder holds no new scene that names missing textures.
    for (const auto& [name, bytes] : files.textures) write_bytes(path.parent_path() / name, mode, bytes);
    write_bytes(path, mode, meta);
}

}  // namespace vksplat::io
