#pragma once
// Writes what torch.save writes, by hand: a zip archive (stored or deflated entries, with the
// padding PyTorch puts in local headers) and a protocol-2 pickle, so that the readers are checked
// against bytes they did not produce.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "io/formats_detail.hpp"
#include "io/io_test_helpers.hpp"

namespace vksplat::io::test {

// ---- a zip writer: stored or deflated entries, with padding in the local headers as PyTorch adds.
struct ZipInput {
    std::string name;
    std::string data;
    bool deflate = false;
    // Written in the directory as zip64 writes entries past 4 GiB: sizes and offset 0xffffffff, the
    // real values in extra field 0x0001.
    bool zip64 = false;
};

inline std::string zip_of(const std::vector<ZipInput>& entries) {
    std::string file, directory;
    for (const auto& entry : entries) {
        const uint32_t crc = detail::crc32_of(entry.data);
        const std::string stored =
            entry.deflate ? detail::deflate_bytes(entry.data, detail::Inflater::Wrapping::raw, "test") : entry.data;
        const uint16_t method = entry.deflate ? 8 : 0;
        const uint32_t offset = static_cast<uint32_t>(file.size());
        // Pad so that the data starts at a multiple of 64, in an extra field as torch.save does.
        const size_t unpadded = file.size() + 30 + entry.name.size() + 4;
        const uint16_t padding = static_cast<uint16_t>((64 - unpadded % 64) % 64);
        append<uint32_t>(file, 0x04034b50);
        append<uint16_t>(file, 20);
        append<uint16_t>(file, 0);
        append<uint16_t>(file, method);
        append<uint16_t>(file, 0);
        append<uint16_t>(file, 0x21);
        append<uint32_t>(file, crc);
        append<uint32_t>(file, static_cast<uint32_t>(stored.size()));
        append<uint32_t>(file, static_cast<uint32_t>(entry.data.size()));
        append<uint16_t>(file, static_cast<uint16_t>(entry.name.size()));
        append<uint16_t>(file, static_cast<uint16_t>(4 + padding));
        file += entry.name;
        append<uint16_t>(file, 0x4650);
        append<uint16_t>(file, padding);
        file += std::string(padding, 'Z');
        file += stored;

        append<uint32_t>(directory, 0x02014b50);
        append<uint16_t>(directory, 20);
        append<uint16_t>(directory, 20);
        append<uint16_t>(directory, 0);
        append<uint16_t>(directory, method);
        append<uint16_t>(directory, 0);
        append<uint16_t>(directory, 0x21);
        append<uint32_t>(directory, crc);
        constexpr uint32_t kInExtraField = 0xffffffff;
        append<uint32_t>(directory, entry.zip64 ? kInExtraField : static_cast<uint32_t>(stored.size()));
        append<uint32_t>(directory, entry.zip64 ? kInExtraField : static_cast<uint32_t>(entry.data.size()));
        append<uint16_t>(directory, static_cast<uint16_t>(entry.name.size()));
        append<uint16_t>(directory, entry.zip64 ? 28 : 0);
        append<uint16_t>(directory, 0);
        append<uint16_t>(directory, 0);
        append<uint16_t>(directory, 0);
        append<uint32_t>(directory, 0);
        append<uint32_t>(directory, entry.zip64 ? kInExtraField : offset);
        directory += entry.name;
        if (entry.zip64) {  // uncompressed size, compressed size, local header offset
            append<uint16_t>(directory, 0x0001);
            append<uint16_t>(directory, 24);
            append<uint64_t>(directory, entry.data.size());
            append<uint64_t>(directory, stored.size());
            append<uint64_t>(directory, offset);
        }
    }
    const uint32_t directory_offset = static_cast<uint32_t>(file.size());
    file += directory;
    append<uint32_t>(file, 0x06054b50);
    append<uint16_t>(file, 0);
    append<uint16_t>(file, 0);
    append<uint16_t>(file, static_cast<uint16_t>(entries.size()));
    append<uint16_t>(file, static_cast<uint16_t>(entries.size()));
    append<uint32_t>(file, static_cast<uint32_t>(directory.size()));
    append<uint32_t>(file, directory_offset);
    append<uint16_t>(file, 0);
    return file;
}

// ---- a pickle writer with the opcodes torch.save (protocol 2) uses.
class Pickle {
public:
    Pickle() { bytes_ = "\x80\x02"; }
    Pickle& op(char opcode) {
        bytes_ += opcode;
        return *this;
    }
    Pickle& mark() { return op('('); }
    Pickle& text(const std::string& value) {
        op('X');
        append<uint32_t>(bytes_, static_cast<uint32_t>(value.size()));
        bytes_ += value;
        return *this;
    }
    Pickle& integer(int64_t value) {
        if (value >= 0 && value < 256) {
            op('K');
            bytes_ += static_cast<char>(value);
        } else if (value >= 0 && value < 65536) {
            op('M');
            append<uint16_t>(bytes_, static_cast<uint16_t>(value));
        } else {
            op('J');
            append<int32_t>(bytes_, static_cast<int32_t>(value));
        }
        return *this;
    }
    Pickle& global(const std::string& module, const std::string& name) {
        op('c');
        bytes_ += module + "\n" + name + "\n";
        return *this;
    }
    Pickle& put(uint8_t index) {
        op('q');
        bytes_ += static_cast<char>(index);
        return *this;
    }
    Pickle& get(uint8_t index) {
        op('h');
        bytes_ += static_cast<char>(index);
        return *this;
    }
    Pickle& ints(const std::vector<int64_t>& values) {
        mark();
        for (int64_t v : values) integer(v);
        return op('t');
    }
    Pickle& ordered_dict() { return global("collections", "OrderedDict").op(')').op('R'); }
    // torch._utils._rebuild_tensor_v2(storage, offset, size, stride, False, OrderedDict()); the storage
    // is new (memoised at `memo`) or, when `shared`, fetched from `memo`.
    Pickle& tensor(const std::string& storage_type, const std::string& key, int64_t numel, int64_t offset,
                   const std::vector<int64_t>& sizes, const std::vector<int64_t>& strides, uint8_t memo,
                   bool shared = false) {
        global("torch._utils", "_rebuild_tensor_v2").mark();
        if (shared) {
            get(memo);
        } else {
            mark().text("storage").global("torch", storage_type).text(key).text("cpu").integer(numel).op('t');
            op('Q').put(memo);
        }
        integer(offset).ints(sizes).ints(strides).op('\x89').ordered_dict().op('t').op('R');
        return *this;
    }
    std::string finish() { return bytes_ + "."; }
    std::string bytes_;
};

}  // namespace vksplat::io::test
