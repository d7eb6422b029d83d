#include "train/checkpoint_file.hpp"

#include <cstring>
#include <fstream>
#include <limits>

#include "train/parameter_layout.hpp"
#include "vksplat/error.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::train {
namespace {

constexpr char kMagic[8] = {'V', 'K', 'S', 'C', 'K', 'P', 'T', '2'};
// The first format, without an owner or densification sums: recognised, never resumed.
constexpr char kMagicV1[8] = {'V', 'K', 'S', 'C', 'K', 'P', 'T', '1'};
// Longer owner strings are not ones vksplat wrote: a corrupt length must not allocate gigabytes.
constexpr uint64_t kMaxOwnerText = 1 << 20;

class Reader {
public:
    explicit Reader(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {}
    bool opened() const { return bool(in_); }

    void bytes(void* out, uint64_t size, const char* what) {
        if (!in_.read(static_cast<char*>(out), std::streamsize(size)))
            throw InputError(path_.string(), std::string("checkpoint is cut short (in its ") + what + ")");
    }
    uint64_t number(const char* what) {
        uint64_t value = 0;
        bytes(&value, sizeof(value), what);
        return value;
    }
    std::string text(const char* what) {
        const uint64_t size = number(what);
        if (size > kMaxOwnerText)
            throw InputError(path_.string(), std::string("checkpoint is corrupt (its ") + what + ")");
        std::string value(size, '\0');
        bytes(value.data(), size, what);
        return value;
    }

private:
    std::filesystem::path path_;
    std::ifstream in_;
};

void put_number(std::ostream& out, uint64_t value) { out.write(reinterpret_cast<const char*>(&value), sizeof(value)); }
void put_text(std::ostream& out, const std::string& value) {
    put_number(out, value.size());
    out.write(value.data(), std::streamsize(value.size()));
}

// Reads the magic and the header into `data`; false when the file is not a vksplat checkpoint.
bool read_header(Reader& reader, const std::filesystem::path& path, CheckpointData& data) {
    char magic[sizeof(kMagic)] = {};
    if (!reader.opened()) return false;
    try {
        reader.bytes(magic, sizeof(magic), "magic");
    } catch (const InputError&) {
        return false;  // shorter than a magic: some other small file
    }
    CheckpointHeader& header = data.header;
    header.records_run = std::memcmp(magic, kMagic, sizeof(magic)) == 0;
    if (!header.records_run && std::memcmp(magic, kMagicV1, sizeof(magic)) != 0) return false;
    header.gaussians = reader.number("header");
    data.sh_degree = reader.number("header");
    header.iteration = reader.number("header");
    data.skipped = reader.number("header");
    if (header.gaussians == 0 || header.gaussians > std::numeric_limits<uint32_t>::max() || data.sh_degree > 3)
        throw InputError(path.string(), "checkpoint header is corrupt (count " + std::to_string(header.gaussians) +
                                            ", SH degree " + std::to_string(data.sh_degree) + ")");
    if (!header.records_run) {
        header.owner.source = "an older vksplat";
        return true;
    }
    header.owner.source = reader.text("owner");
    const uint64_t fields = reader.number("owner");
    if (fields > 64) throw InputError(path.string(), "checkpoint is corrupt (its owner)");
    for (uint64_t i = 0; i < fields; ++i) {
        std::string name = reader.text("owner");
        header.owner.fields.emplace_back(std::move(name), reader.text("owner"));
    }
    return true;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const CheckpointData& data, io::WriteMode mode) {
    io::write_file_atomically(path, mode, [&](std::ostream& out) {
        out.write(kMagic, sizeof(kMagic));
        const CheckpointHeader& header = data.header;
        for (uint64_t value : {header.gaussians, data.sh_degree, header.iteration, data.skipped})
            put_number(out, value);
        put_text(out, header.owner.source);
        put_number(out, header.owner.fields.size());
        for (const auto& [name, value] : header.owner.fields) {
            put_text(out, name);
            put_text(out, value);
        }
        for (const auto* array : {&data.params, &data.first_moment, &data.second_moment, &data.densify_sums})
            out.write(reinterpret_cast<const char*>(array->data()), std::streamsize(array->size() * sizeof(float)));
    });
}

CheckpointData read_checkpoint(const std::filesystem::path& path, const CheckpointOwner& expected) {
    Reader reader(path);
    if (!reader.opened()) throw InputError(path.string(), "cannot open the checkpoint");
    CheckpointData data;
    if (!read_header(reader, path, data)) throw InputError(path.string(), "not a vksplat training checkpoint");
    check_checkpoint_owner(path, data.header, expected);
    const uint64_t count = data.header.gaussians;
    const uint64_t floats =
        ParameterLayout{uint32_t(count), uint32_t(sh_coefficients_for_degree(int(data.sh_degree)))}.total();
    for (auto* array : {&data.params, &data.first_moment, &data.second_moment}) {
        array->resize(floats);
        reader.bytes(array->data(), floats * sizeof(float), "parameters");
    }
    data.densify_sums.resize(count * kDensifyStride);
    reader.bytes(data.densify_sums.data(), data.densify_sums.size() * sizeof(float), "densification sums");
    return data;
}

std::optional<CheckpointHeader> read_checkpoint_header(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
    Reader reader(path);
    CheckpointData data;
    if (!read_header(reader, path, data)) return std::nullopt;
    return std::move(data.header);
}

void check_checkpoint_owner(const std::filesystem::path& path, const CheckpointHeader& checkpoint,
                            const CheckpointOwner& expected) {
    if (!checkpoint.records_run)
        throw InputError(path.string(), "is a checkpoint of an older vksplat, which recorded neither the run it "
                                        "belongs to nor the densification state; it cannot be resumed safely "
                                        "(--force starts over and replaces it)");
    const CheckpointOwner& found = checkpoint.owner;
    const auto value_of = [](const CheckpointOwner& owner, const std::string& name) -> std::string {
        for (const auto& [key, value] : owner.fields)
            if (key == name) return value;
        return "(none)";
    };
    std::vector<std::string> names;
    for (const auto& [name, value] : expected.fields) names.push_back(name);
    for (const auto& [name, value] : found.fields) names.push_back(name);
    for (const auto& name : names) {
        const std::string was = value_of(found, name), now = value_of(expected, name);
        if (was != now)
            throw InputError(path.string(), "was made by another run (" + found.source + "): its " + name + " is " +
                                                was + ", this run's is " + now +
                                                "; --force starts over and replaces it");
    }
}

}  // namespace vksplat::train
