// gsplat checkpoints as torch.save writes them: a zip archive holding `<name>/data.pkl` (a pickle of
// the saved object, whose tensors refer to storages by key) and `<name>/data/<key>` (the raw bytes
// of each storage). The archive and the pickle have readers of their own (zip_archive.hpp,
// pickle.hpp); this file gathers each tensor's values, honouring sizes, strides, offsets and
// dtypes, and builds the Gaussian cloud from gsplat's `splats` dictionary.
#include <algorithm>
#include <cstring>
#include <map>
#include <set>

#include "io/byte_order.hpp"
#include "io/pickle.hpp"
#include "io/zip_archive.hpp"
#include "vksplat/error.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;
using pickle::Ref;
using pickle::Value;

// Tensors

float half_to_float(uint16_t h) {
    const uint32_t sign = uint32_t{h & 0x8000u} << 16;
    const uint32_t exponent = (h >> 10) & 0x1f;
    uint32_t mantissa = h & 0x3ffu;
    uint32_t bits = 0;
    if (exponent == 0) {
        if (mantissa == 0) {
            bits = sign;
        } else {  // subnormal: normalise
            int e = -1;
            do {
                ++e;
                mantissa <<= 1;
            } while (!(mantissa & 0x400u));
            bits = sign | ((127 - 15 - e) << 23) | ((mantissa & 0x3ffu) << 13);
        }
    } else if (exponent == 31) {
        bits = sign | 0x7f800000u | (mantissa << 13);
    } else {
        bits = sign | ((exponent + 127 - 15) << 23) | (mantissa << 13);
    }
    float value;
    std::memcpy(&value, &bits, 4);
    return value;
}

struct DType {
    const char* storage;
    const char* name;
    size_t bytes;
};
constexpr DType kFloatTypes[] = {{"torch.FloatStorage", "float32", 4},
                                 {"torch.HalfStorage", "float16", 2},
                                 {"torch.BFloat16Storage", "bfloat16", 2},
                                 {"torch.DoubleStorage", "float64", 8}};

class TensorReader {
public:
    TensorReader(zip::Archive& archive, std::string prefix, bool swap, std::string where)
        : archive_(archive), prefix_(std::move(prefix)), swap_(swap), where_(std::move(where)) {}

    // The tensor's values in row-major order of its sizes, as float.
    std::vector<float> gather(const Value& tensor, const std::string& name) {
        const std::string at = where_ + ": tensor '" + name + "'";
        const Value& storage = *tensor.storage;
        const DType* dtype = nullptr;
        for (const auto& type : kFloatTypes)
            if (storage.text == type.storage) dtype = &type;
        if (!dtype) throw InputError(at, "has storage type " + storage.text + "; expected a floating-point tensor");

        // Elements the view reaches: offset + sum((size - 1) * stride) must lie within the storage.
        uint64_t count = 1;
        uint64_t last = static_cast<uint64_t>(tensor.offset);
        bool overflow = false;
        for (size_t d = 0; d < tensor.sizes.size(); ++d) {
            const auto size = static_cast<uint64_t>(tensor.sizes[d]);
            if (__builtin_mul_overflow(count, size, &count)) throw InputError(at, "element count overflows");
            uint64_t reach = 0;
            if (size > 0 && (__builtin_mul_overflow(size - 1, static_cast<uint64_t>(tensor.strides[d]), &reach) ||
                             __builtin_add_overflow(last, reach, &last)))
                overflow = true;
        }
        if (count > 0 && (overflow || last >= static_cast<uint64_t>(storage.numel)))
            throw InputError(at, "reaches " + (overflow ? std::string("beyond 2^64 elements") : "element " + std::to_string(last)) +
                                     " of storage '" + storage.key + "', which has only " +
                                     std::to_string(storage.numel) + " (sizes, strides or offset are corrupt)");
        // A view that repeats elements (a zero stride) may hold more than its storage; a parameter
        // never does, and allowing it would let a few bytes describe 2^40 Gaussians.
        if (count > static_cast<uint64_t>(storage.numel))
            throw InputError(at, "has " + std::to_string(count) + " elements but its storage '" + storage.key +
                                     "' only " + std::to_string(storage.numel) +
                                     " (a broadcast view, or corrupt sizes and strides)");

        const std::string& bytes = storage_bytes(storage, *dtype, at);
        std::vector<float> values(count);
        std::vector<uint64_t> index(tensor.sizes.size(), 0);
        for (uint64_t i = 0; i < count; ++i) {
            uint64_t element = static_cast<uint64_t>(tensor.offset);
            for (size_t d = 0; d < index.size(); ++d) element += index[d] * static_cast<uint64_t>(tensor.strides[d]);
            values[i] = load(bytes.data() + element * dtype->bytes, *dtype);
            for (size_t d = index.size(); d-- > 0;) {
                if (++index[d] < static_cast<uint64_t>(tensor.sizes[d])) break;
                index[d] = 0;
            }
        }
        return values;
    }

private:
    float load(const char* bytes, const DType& dtype) const {
        switch (dtype.bytes) {
            case 4:
                return detail::load_scalar<float>(bytes, swap_);
            case 8:
                return static_cast<float>(detail::load_scalar<double>(bytes, swap_));
            default: {
                const auto bits = detail::load_scalar<uint16_t>(bytes, swap_);
                if (dtype.storage == std::string_view("torch.HalfStorage")) return half_to_float(bits);
                const uint32_t wide = uint32_t{bits} << 16;
                float value;
                std::memcpy(&value, &wide, 4);
                return value;
            }
        }
    }

    const std::string& storage_bytes(const Value& storage, const DType& dtype, const std::string& at) {
        if (const auto found = cache_.find(storage.key); found != cache_.end()) return found->second;
        const std::string entry_name = prefix_ + "data/" + storage.key;
        const zip::Entry* entry = archive_.find(entry_name);
        if (!entry) throw InputError(at, "its storage '" + entry_name + "' is missing from the archive");
        uint64_t needed = 0;
        if (__builtin_mul_overflow(static_cast<uint64_t>(storage.numel), dtype.bytes, &needed) || entry->size < needed)
            throw InputError(at, "storage '" + entry_name + "' holds " + std::to_string(entry->size) + " bytes but " +
                                     std::to_string(storage.numel) + " " + dtype.name + " elements need " +
                                     std::to_string(needed) + " (truncated?)");
        return cache_.emplace(storage.key, archive_.read(*entry)).first->second;
    }

    zip::Archive& archive_;
    std::string prefix_;
    bool swap_;
    std::string where_;
    std::map<std::string, std::string> cache_;
};

std::string shape_text(const std::vector<int64_t>& sizes) {
    std::string text = "[";
    for (size_t d = 0; d < sizes.size(); ++d) text += (d ? ", " : "") + std::to_string(sizes[d]);
    return text + "]";
}

}  // namespace

GaussianCloud read_gsplat_checkpoint(const fs::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    zip::Archive archive(path, where);

    // torch.save names every entry "<archive name>/...": find the pickle to learn the prefix.
    const zip::Entry* pickle_entry = nullptr;
    for (const auto& entry : archive.entries()) {
        const std::string& name = entry.name;
        const bool is_pickle = name == "data.pkl" || (name.size() > 9 && name.compare(name.size() - 9, 9, "/data.pkl") == 0);
        if (is_pickle && (!pickle_entry || name.size() < pickle_entry->name.size())) pickle_entry = &entry;
    }
    if (!pickle_entry) throw InputError(where, "not a PyTorch checkpoint: the zip archive has no data.pkl");
    const std::string prefix = pickle_entry->name.substr(0, pickle_entry->name.size() - 8);
    bool swap = !detail::kHostIsLittleEndian;
    if (const zip::Entry* order = archive.find(prefix + "byteorder")) {
        const std::string text = archive.read(*order);
        if (text != "little" && text != "big") throw InputError(where, "unknown byte order '" + text + "'");
        swap = (text == "big") == detail::kHostIsLittleEndian;
    }

    const Ref root = pickle::load(archive.read(*pickle_entry), where + ": " + pickle_entry->name);
    if (root->kind != Value::Kind::dict) throw InputError(where, "the checkpoint is not a dictionary");
    Ref splats = pickle::dict_get(*root, "splats");
    if (!splats && pickle::dict_get(*root, "means")) splats = root;
    if (!splats || splats->kind != Value::Kind::dict) {
        std::string keys;
        for (const auto& [key, value] : root->entries)
            if (key->kind == Value::Kind::text) keys += (keys.empty() ? "" : ", ") + key->text;
        throw InputError(where, "has no 'splats' dictionary of tensors (top-level keys: " +
                                    (keys.empty() ? std::string("none") : keys) + ")");
    }

    const auto tensor = [&](const std::string& name, bool required) -> Ref {
        const Ref value = pickle::dict_get(*splats, name);
        if (!value) {
            if (required) throw InputError(where, "splats has no '" + name + "' tensor");
            return nullptr;
        }
        if (value->kind != Value::Kind::tensor)
            throw InputError(where, "splats['" + name + "'] is not a tensor");
        return value;
    };
    const Ref means = tensor("means", true);
    const Ref quats = tensor("quats", true);
    const Ref scales = tensor("scales", true);
    const Ref opacities = tensor("opacities", true);
    const Ref sh0 = tensor("sh0", true);
    const Ref sh_rest = tensor("shN", false);

    if (means->sizes.size() != 2 || means->sizes[1] != 3)
        throw InputError(where, "tensor 'means' has shape " + shape_text(means->sizes) + "; expected [N, 3]");
    const int64_t n = means->sizes[0];
    const auto expect_shape = [&](const Ref& t, const std::string& name, std::vector<std::vector<int64_t>> shapes,
                                  const std::string& expected) {
        for (const auto& shape : shapes)
            if (t->sizes == shape) return;
        throw InputError(where, "tensor '" + name + "' has shape " + shape_text(t->sizes) + "; expected " + expected +
                                    " with N = " + std::to_string(n) + " (from 'means')");
    };
    expect_shape(quats, "quats", {{n, 4}}, "[N, 4]");
    expect_shape(scales, "scales", {{n, 3}}, "[N, 3]");
    expect_shape(opacities, "opacities", {{n}, {n, 1}}, "[N]");
    expect_shape(sh0, "sh0", {{n, 1, 3}, {n, 3}}, "[N, 1, 3]");
    int sh_degree = 0;
    if (sh_rest) {
        const int64_t k = sh_rest->sizes.size() == 3 ? sh_rest->sizes[1] : -1;
        for (int degree = 0; degree <= 3; ++degree)
            if (k == sh_coefficients_for_degree(degree) - 1) sh_degree = degree;
        if (sh_rest->sizes.size() != 3 || sh_rest->sizes[0] != n || sh_rest->sizes[2] != 3 ||
            k != sh_coefficients_for_degree(sh_degree) - 1)
            throw InputError(where, "tensor 'shN' has shape " + shape_text(sh_rest->sizes) +
                                        "; expected [N, K, 3] with K = 0, 3, 8 or 15 and N = " + std::to_string(n));
    }

    // Gathered before the cloud is sized for n: gather checks each tensor against the bytes really in
    // the archive, so n is then known to be backed by data.
    TensorReader reader(archive, prefix, swap, where);
    std::vector<float> positions = reader.gather(*means, "means");
    std::vector<float> rotations = reader.gather(*quats, "quats");  // gsplat's quaternions are w, x, y, z too
    std::vector<float> log_scales = reader.gather(*scales, "scales");
    std::vector<float> opacity_logits = reader.gather(*opacities, "opacities");
    const std::vector<float> dc = reader.gather(*sh0, "sh0");
    const std::vector<float> rest = sh_rest ? reader.gather(*sh_rest, "shN") : std::vector<float>{};
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(static_cast<size_t>(n));
    cloud.positions = std::move(positions);
    cloud.rotations = std::move(rotations);
    cloud.log_scales = std::move(log_scales);
    cloud.opacity_logits = std::move(opacity_logits);
    // Both are [coefficient][rgb] per Gaussian, as the cloud is: DC first, then the rest.
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
        std::copy_n(dc.begin() + static_cast<std::ptrdiff_t>(i * 3), 3, cloud.sh.begin() + static_cast<std::ptrdiff_t>(i * coefficients * 3));
        std::copy_n(rest.begin() + static_cast<std::ptrdiff_t>(i * (coefficients - 1) * 3), (coefficients - 1) * 3,
                    cloud.sh.begin() + static_cast<std::ptrdiff_t>(i * coefficients * 3 + 3));
    }

    if (notes) {
        std::string ignored;
        for (const auto& [key, value] : splats->entries) {
            if (key->kind != Value::Kind::text) continue;
            static const std::set<std::string> used = {"means", "quats", "scales", "opacities", "sh0", "shN"};
            if (!used.count(key->text)) ignored += (ignored.empty() ? "" : ", ") + key->text;
        }
        if (!ignored.empty())
            notes->push_back(where + ": ignored splats entries " + ignored + " (a Gaussian cloud has no place for them)");
        if (const Ref step = pickle::dict_get(*root, "step"); step && step != splats && step->kind == Value::Kind::integer)
            notes->push_back(where + ": checkpoint of step " + std::to_string(step->integer));
    }
    return cloud;
}

}  // namespace vksplat::io