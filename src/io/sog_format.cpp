// Reads PlayCanvas SOG version 2 (io/sog_layout.hpp): a .sog zip, or a meta.json beside its
// textures. Everything the file says is checked before it is used: meta.json's keys and their
// types, that each texture is there and a WebP, that the per-splat textures share one size that
// holds every splat, and that every index stays inside its codebook or palette.
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>

#include "io/formats_detail.hpp"
#include "io/json_fields.hpp"
#include "io/sog_layout.hpp"
#include "io/webp_image.hpp"
#include "io/zip_archive.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;
using detail::RgbaImage;
using nlohmann::json;

// Where a SOG's files come from: the entries of its zip, or the files beside its meta.json. A file
// is told apart by its first bytes, not its name: a zip's local header or empty directory, or JSON.
class SogSource {
public:
    explicit SogSource(const fs::path& path) : path_(path) {
        const std::string head = first_bytes(path, 4);
        if (head == std::string("PK\x03\x04", 4) || head == std::string("PK\x05\x06", 4)) {
            archive_.emplace(path, path.string());
        } else if (!detail::sog::is_meta_json(path) && head.find('{') == std::string::npos) {
            throw InputError(path.string(), "not a SOG scene: neither a zip archive (.sog) nor a meta.json");
        }
    }

    std::string meta_where() const {
        return archive_ ? path_.string() + ": " + detail::sog::kMetaName : path_.string();
    }
    std::string where(const std::string& name) const {
        return archive_ ? path_.string() + ": " + name : (path_.parent_path() / name).string();
    }

    std::string meta() { return archive_ ? entry(detail::sog::kMetaName) : detail::read_file_bytes(path_, path_.string()); }

    std::string texture(const std::string& name) {
        if (archive_) return entry(name);
        const fs::path file = path_.parent_path() / name;
        if (!fs::exists(file))
            throw InputError(where(name), std::string("missing: ") + detail::sog::kMetaName + " names this texture");
        return detail::read_file_bytes(file, file.string());
    }

private:
    static std::string first_bytes(const fs::path& path, size_t count) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw InputError(path.string(), fs::exists(path) ? "cannot be opened" : "no such file");
        std::string bytes(count, '\0');
        in.read(bytes.data(), std::streamsize(count));
        bytes.resize(size_t(in.gcount()));
        return bytes;
    }

    std::string entry(const std::string& name) {
        const zip::Entry* found = archive_->find(name);
        if (!found)
            throw InputError(where(name), name == detail::sog::kMetaName
                                              ? std::string("missing: the archive holds no meta.json")
                                              : std::string("missing from the archive: meta.json names this texture"));
        return archive_->read(*found);
    }

    fs::path path_;
    std::optional<zip::Archive> archive_;
};

// meta.json, checked: what it says and the names of the textures.
struct Meta {
    size_t count = 0;
    double mins[3] = {}, maxs[3] = {};
    std::vector<std::string> means_files, quats_files, scales_files, sh0_files, sh_files;
    std::vector<float> scales_codebook, sh0_codebook, sh_codebook;
    int sh_bands = 0;
    size_t palette_entries = 0;
};

size_t count_field(const json& object, const char* key, const std::string& at) {
    const int value = detail::int_field(object, key, at);
    if (value < 0) throw InputError(at, std::string("key '") + key + "' is negative (" + std::to_string(value) + ")");
    return size_t(value);
}

// The texture names under `key`, at least `count` of them, each a plain file name: a SOG's
// textures lie beside its meta.json, never elsewhere.
std::vector<std::string> file_names(const json& object, const char* key, size_t count, const std::string& at) {
    const json& files = detail::field(object, "files", at + "." + key);
    if (!files.is_array() || files.size() < count)
        throw InputError(at, std::string("key '") + key + ".files' is not a list of " + std::to_string(count) +
                                 " texture names");
    std::vector<std::string> names;
    for (const json& name : files) {
        const std::string text = name.is_string() ? name.get<std::string>() : "";
        if (text.empty() || text == "." || text == ".." || text.find_first_of("/\\") != std::string::npos)
            throw InputError(at, std::string("key '") + key + ".files' holds " + name.dump() +
                                     ", not the file name of a texture beside meta.json");
        names.push_back(text);
    }
    return names;
}

std::vector<float> codebook_field(const json& object, const char* key, const std::string& at) {
    const json& values = detail::field(object, "codebook", at + "." + key);
    std::vector<float> codebook;
    if (values.is_array())
        for (const json& value : values)
            if (value.is_number() && std::isfinite(value.get<double>())) codebook.push_back(value.get<float>());
    if (codebook.empty() || codebook.size() != values.size())
        throw InputError(at, std::string("key '") + key + ".codebook' is not a list of finite numbers");
    return codebook;
}

Meta read_meta(SogSource& source) {
    const std::string at = source.meta_where();
    const json meta = detail::parse_json(source.meta(), at);
    if (!meta.is_object()) throw InputError(at, std::string("is a JSON ") + meta.type_name() + ", expected an object");
    if (!meta.contains("version"))
        throw InputError(at, "has no 'version': a SOG of the first version, which is not read (only version 2, "
                             "what splat-transform and SuperSplat write now)");
    if (const int version = detail::int_field(meta, "version", at); version != detail::sog::kVersion)
        throw InputError(at, "SOG version " + std::to_string(version) + " is not supported (only version 2)");
    Meta result;
    result.count = count_field(meta, "count", at);
    const json& means = detail::field(meta, "means", at);
    const auto mins = detail::matrix_field(means, "mins", 1, 3, at + ": means");
    const auto maxs = detail::matrix_field(means, "maxs", 1, 3, at + ": means");
    // Beyond this a log-encoded coordinate decodes to more than a float holds.
    const double largest = std::log1p(double(std::numeric_limits<float>::max()));
    for (size_t a = 0; a < 3; ++a) {
        result.mins[a] = mins[a];
        result.maxs[a] = maxs[a];
        if (!(std::abs(mins[a]) <= largest && std::abs(maxs[a]) <= largest))
            throw InputError(at, "means.mins and maxs are not log-encoded coordinates a float holds (|v| <= " +
                                     std::to_string(largest) + ")");
    }
    result.means_files = file_names(means, "means", 2, at);
    result.quats_files = file_names(detail::field(meta, "quats", at), "quats", 1, at);
    const json& scales = detail::field(meta, "scales", at);
    result.scales_codebook = codebook_field(scales, "scales", at);
    result.scales_files = file_names(scales, "scales", 1, at);
    const json& sh0 = detail::field(meta, "sh0", at);
    result.sh0_codebook = codebook_field(sh0, "sh0", at);
    result.sh0_files = file_names(sh0, "sh0", 1, at);
    if (meta.contains("shN")) {
        const json& sh = meta["shN"];
        result.sh_bands = detail::int_field(sh, "bands", at + ": shN");
        if (result.sh_bands < 1 || result.sh_bands > 3)
            throw InputError(at, "shN.bands is " + std::to_string(result.sh_bands) + ", expected 1, 2 or 3");
        result.palette_entries = count_field(sh, "count", at + ": shN");
        result.sh_codebook = codebook_field(sh, "shN", at);
        result.sh_files = file_names(sh, "shN", 2, at);
    }
    return result;
}

// Decodes the per-splat textures and checks that they agree in size and hold every splat.
class TextureReader {
public:
    TextureReader(SogSource& source, size_t count) : source_(source), count_(count) {}

    RgbaImage per_splat(const std::string& name) {
        RgbaImage image = detail::decode_webp(source_.texture(name), source_.where(name));
        const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
        if (!first_) {
            if (size_t(image.width) * size_t(image.height) < count_)
                throw InputError(source_.where(name), "wrong texture size: " + size + " holds " +
                                                          std::to_string(size_t(image.width) * size_t(image.height)) +
                                                          " splats, fewer than the " + std::to_string(count_) +
                                                          " meta.json counts");
            first_ = {name, image.width, image.height};
        } else if (image.width != first_->width || image.height != first_->height) {
            throw InputError(source_.where(name), "wrong texture size: " + size + ", where " + first_->name + " is " +
                                                      std::to_string(first_->width) + "x" +
                                                      std::to_string(first_->height) +
                                                      " (every per-splat texture has the same size)");
        }
        return image;
    }

    RgbaImage any(const std::string& name) { return detail::decode_webp(source_.texture(name), source_.where(name)); }
    std::string where(const std::string& name) const { return source_.where(name); }

private:
    struct Size {
        std::string name;
        int width, height;
    };
    SogSource& source_;
    size_t count_;
    std::optional<Size> first_;
};

// codebook[index], or InputError naming the texture and texel that points past it.
float look_up(const std::vector<float>& codebook, uint8_t index, const TextureReader& textures,
              const std::string& name, size_t texel) {
    if (index >= codebook.size())
        throw InputError(textures.where(name), "texel " + std::to_string(texel) + " indexes entry " +
                                                   std::to_string(index) + " of a codebook of " +
                                                   std::to_string(codebook.size()));
    return codebook[index];
}

void read_sh_rest(const Meta& meta, TextureReader& textures, GaussianCloud& cloud) {
    const int coefficients = detail::sog::rest_coefficients(meta.sh_bands);
    const std::string& centroids_name = meta.sh_files[0];
    const std::string& labels_name = meta.sh_files[1];
    const RgbaImage centroids = textures.any(centroids_name);
    const int per_row = detail::sog::kPaletteEntriesPerRow;
    if (centroids.width != per_row * coefficients)
        throw InputError(textures.where(centroids_name),
                         "wrong texture size: " + std::to_string(centroids.width) + " texels wide, where SH of " +
                             std::to_string(meta.sh_bands) + " bands take " + std::to_string(per_row * coefficients) +
                             " (64 palette entries of " + std::to_string(coefficients) + " coefficients)");
    const size_t entries = std::min(meta.palette_entries, size_t(centroids.height) * per_row);
    const RgbaImage labels = textures.per_splat(labels_name);
    const size_t stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 0; i < cloud.size(); ++i) {
        const size_t entry = labels.rgba[i * 4] | size_t(labels.rgba[i * 4 + 1]) << 8;
        if (entry >= entries)
            throw InputError(textures.where(labels_name),
                             "texel " + std::to_string(i) + " names palette entry " + std::to_string(entry) +
                                 ", beyond the " + std::to_string(entries) + " that meta.json and " + centroids_name +
                                 " hold");
        const size_t first_texel = (entry / per_row) * size_t(centroids.width) + (entry % per_row) * coefficients;
        for (int j = 0; j < coefficients; ++j)
            for (size_t c = 0; c < 3; ++c) {
                const size_t texel = first_texel + size_t(j);
                cloud.sh[i * stride + 3 + size_t(j) * 3 + c] =
                    look_up(meta.sh_codebook, centroids.rgba[texel * 4 + c], textures, centroids_name, texel);
            }
    }
}

}  // namespace

GaussianCloud read_sog(const fs::path& path, std::vector<std::string>* /*notes*/) {
    SogSource source(path);
    const Meta meta = read_meta(source);
    TextureReader textures(source, meta.count);
    // The first texture bounds the count before the cloud is made for it.
    const RgbaImage lower = textures.per_splat(meta.means_files[0]);
    const RgbaImage upper = textures.per_splat(meta.means_files[1]);
    GaussianCloud cloud;
    cloud.sh_degree = meta.sh_bands;
    cloud.resize(meta.count);
    const size_t n = meta.count, stride = size_t(cloud.sh_coefficients()) * 3;
    for (size_t i = 0; i < n; ++i)
        for (size_t a = 0; a < 3; ++a) {
            const double q = lower.rgba[i * 4 + a] | uint32_t(upper.rgba[i * 4 + a]) << 8;
            const double v = meta.mins[a] + (meta.maxs[a] - meta.mins[a]) * q / 65535.0;
            cloud.positions[i * 3 + a] = static_cast<float>(detail::sog::log_decode(v));
        }

    const std::string& quats_name = meta.quats_files[0];
    const RgbaImage quats = textures.per_splat(quats_name);
    for (size_t i = 0; i < n; ++i) {
        const int largest = quats.rgba[i * 4 + 3] - detail::sog::kQuaternionTagBase;
        if (largest < 0 || largest > 3)
            throw InputError(textures.where(quats_name), "texel " + std::to_string(i) + " has alpha " +
                                                             std::to_string(quats.rgba[i * 4 + 3]) +
                                                             ", not 252 to 255 (which component is left out)");
        double q[4], others = 0;
        for (int k = 0, slot = 0; k < 4; ++k)
            if (k != largest) {
                q[k] = (quats.rgba[i * 4 + slot++] / 255.0 * 2.0 - 1.0) / detail::sog::kSqrt2;
                others += q[k] * q[k];
            }
        q[largest] = std::sqrt(std::max(0.0, 1.0 - others));
        for (int k = 0; k < 4; ++k) cloud.rotations[i * 4 + size_t(k)] = static_cast<float>(q[k]);
    }

    const std::string& scales_name = meta.scales_files[0];
    const RgbaImage scales = textures.per_splat(scales_name);
    for (size_t i = 0; i < n; ++i)
        for (size_t a = 0; a < 3; ++a)
            cloud.log_scales[i * 3 + a] = look_up(meta.scales_codebook, scales.rgba[i * 4 + a], textures, scales_name, i);

    const std::string& sh0_name = meta.sh0_files[0];
    const RgbaImage sh0 = textures.per_splat(sh0_name);
    for (size_t i = 0; i < n; ++i) {
        for (size_t c = 0; c < 3; ++c)
            cloud.sh[i * stride + c] = look_up(meta.sh0_codebook, sh0.rgba[i * 4 + c], textures, sh0_name, i);
        cloud.opacity_logits[i] = detail::logit_of(sh0.rgba[i * 4 + 3] / 255.0);
    }

    if (meta.sh_bands > 0) read_sh_rest(meta, textures, cloud);
    return cloud;
}

}  // namespace vksplat::io
