#include "io/zip_archive.hpp"

#include <algorithm>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io::zip {
namespace {

namespace fs = std::filesystem;

template <typename T>
T le(const std::string& bytes, size_t offset) {
    return detail::load_little_endian<T>(bytes.data() + offset);
}

}  // namespace

Archive::Archive(const fs::path& path, std::string where) : where_(std::move(where)), in_(path, std::ios::binary) {
    if (!in_) throw InputError(where_, fs::exists(path) ? "cannot be opened" : "no such file");
    file_size_ = fs::file_size(path);
    read_directory();
}

const Entry* Archive::find(const std::string& name) const {
    for (const auto& entry : entries_)
        if (entry.name == name) return &entry;
    return nullptr;
}

std::string Archive::read(const Entry& entry) {
    const std::string at = where_ + ": zip entry '" + entry.name + "'";
    const std::string local = bytes_at(entry.local_offset, 30, at + ": local header");
    if (le<uint32_t>(local, 0) != 0x04034b50) throw InputError(at, "bad local header signature (corrupt zip)");
    const uint64_t data_offset = entry.local_offset + 30 + le<uint16_t>(local, 26) + le<uint16_t>(local, 28);
    if (le<uint16_t>(local, 6) & 0x1) throw InputError(at, "is encrypted, which is not supported");
    std::string data;
    if (entry.method == 0) {
        if (entry.compressed_size != entry.size)
            throw InputError(at, "stored entry's sizes disagree (" + std::to_string(entry.compressed_size) +
                                     " vs " + std::to_string(entry.size) + ")");
        data = bytes_at(data_offset, entry.size, at);
    } else if (entry.method == 8) {
        const std::string compressed = bytes_at(data_offset, entry.compressed_size, at);
        detail::Inflater inflater(compressed, detail::Inflater::Wrapping::raw, at);
        if (inflater.read(data, entry.size) != entry.size)
            throw InputError(at, "truncated: inflates to " + std::to_string(data.size()) + " bytes, expected " +
                                     std::to_string(entry.size));
        if (!inflater.at_end()) throw InputError(at, "inflates to more than its stated " + std::to_string(entry.size) + " bytes");
    } else {
        throw InputError(at, "uses compression method " + std::to_string(entry.method) +
                                 " (only stored (0) and deflate (8) are supported)");
    }
    if (detail::crc32_of(data) != entry.crc) throw InputError(at, "CRC mismatch: the data is corrupt");
    return data;
}

std::string Archive::bytes_at(uint64_t offset, uint64_t count, const std::string& at) {
    if (offset > file_size_ || count > file_size_ - offset)
        throw InputError(at, "truncated: needs bytes " + std::to_string(offset) + " to " +
                                 std::to_string(offset + count) + " but the file has " + std::to_string(file_size_));
    std::string bytes(count, '\0');
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    if (!in_.read(bytes.data(), static_cast<std::streamsize>(count)))
        throw InputError(at, "reading " + std::to_string(count) + " bytes failed");
    return bytes;
}

void Archive::read_directory() {
    // The end-of-central-directory record: 22 bytes plus a comment of up to 65535 at the end.
    const uint64_t tail_size = std::min<uint64_t>(file_size_, 22 + 65535);
    if (file_size_ < 22)
        throw InputError(where_, "too short (" + std::to_string(file_size_) + " bytes) to be a zip archive");
    const std::string tail = bytes_at(file_size_ - tail_size, tail_size, where_);
    size_t eocd = std::string::npos;
    for (size_t i = tail_size - 22 + 1; i-- > 0;)
        if (le<uint32_t>(tail, i) == 0x06054b50) {
            eocd = i;
            break;
        }
    if (eocd == std::string::npos) {
        const bool legacy = tail_size >= 2 && static_cast<uint8_t>(tail[0]) == 0x80;
        throw InputError(where_, std::string("not a zip archive (no end-of-central-directory record): ") +
                                     (legacy ? "a legacy (pre-1.6) torch.save file is not supported; re-save "
                                               "it with a recent PyTorch"
                                             : "wrong magic or truncated"));
    }
    uint64_t entry_count = le<uint16_t>(tail, eocd + 10);
    uint64_t directory_size = le<uint32_t>(tail, eocd + 12);
    uint64_t directory_offset = le<uint32_t>(tail, eocd + 16);
    const uint64_t eocd_offset = file_size_ - tail_size + eocd;
    if ((entry_count == 0xffff || directory_size == 0xffffffff || directory_offset == 0xffffffff) &&
        eocd_offset >= 20) {
        const std::string locator = bytes_at(eocd_offset - 20, 20, where_ + ": zip64 locator");
        if (le<uint32_t>(locator, 0) == 0x07064b50) {
            const std::string record = bytes_at(le<uint64_t>(locator, 8), 56, where_ + ": zip64 directory record");
            if (le<uint32_t>(record, 0) != 0x06064b50)
                throw InputError(where_, "bad zip64 end-of-central-directory signature (corrupt zip)");
            entry_count = le<uint64_t>(record, 32);
            directory_size = le<uint64_t>(record, 40);
            directory_offset = le<uint64_t>(record, 48);
        }
    }
    if (directory_offset > file_size_ || directory_size > file_size_ - directory_offset)
        throw InputError(where_, "truncated: the zip directory (" + std::to_string(directory_size) + " bytes at " +
                                     std::to_string(directory_offset) + ") lies beyond the end of the file (" +
                                     std::to_string(file_size_) + " bytes)");
    if (entry_count > directory_size / 46)
        throw InputError(where_, "zip directory claims " + std::to_string(entry_count) + " entries but has room for " +
                                     std::to_string(directory_size / 46));
    const std::string directory = bytes_at(directory_offset, directory_size, where_);
    size_t at = 0;
    for (uint64_t e = 0; e < entry_count; ++e) {
        if (directory.size() - at < 46 || le<uint32_t>(directory, at) != 0x02014b50)
            throw InputError(where_, "corrupt zip directory at entry " + std::to_string(e));
        Entry entry;
        entry.method = le<uint16_t>(directory, at + 10);
        entry.crc = le<uint32_t>(directory, at + 16);
        entry.compressed_size = le<uint32_t>(directory, at + 20);
        entry.size = le<uint32_t>(directory, at + 24);
        const size_t name_length = le<uint16_t>(directory, at + 28);
        const size_t extra_length = le<uint16_t>(directory, at + 30);
        const size_t comment_length = le<uint16_t>(directory, at + 32);
        entry.local_offset = le<uint32_t>(directory, at + 42);
        if (directory.size() - at - 46 < name_length + extra_length + comment_length)
            throw InputError(where_, "corrupt zip directory at entry " + std::to_string(e));
        entry.name = directory.substr(at + 46, name_length);
        // Zip64: the sizes and offset that overflowed 32 bits are in extra field 0x0001, in order.
        for (size_t x = at + 46 + name_length; x + 4 <= at + 46 + name_length + extra_length;) {
            const uint16_t id = le<uint16_t>(directory, x);
            const uint16_t length = le<uint16_t>(directory, x + 2);
            if (id == 0x0001) {
                size_t field = x + 4;
                const size_t end = x + 4 + length;
                for (uint64_t* value : {&entry.size, &entry.compressed_size, &entry.local_offset})
                    if (*value == 0xffffffff && field + 8 <= end) {
                        *value = le<uint64_t>(directory, field);
                        field += 8;
                    }
            }
            x += 4 + length;
        }
        entries_.push_back(std::move(entry));
        at += 46 + name_length + extra_length + comment_length;
    }
}

std::string stored_archive(const std::vector<std::pair<std::string, std::string>>& files, const std::string& where) {
    constexpr uint16_t kVersion = 20;             // 2.0: the first with folders and deflate; enough for stored
    constexpr uint16_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, the earliest a zip can say
    constexpr uint64_t kLimit = 0xffffffff;      // beyond it, sizes and offsets need zip64
    if (files.size() >= 0xffff)
        throw InputError(where, std::to_string(files.size()) + " entries need zip64, which is not written");
    std::string archive, directory;
    for (const auto& [name, bytes] : files) {
        const uint64_t offset = archive.size();
        if (bytes.size() >= kLimit || offset >= kLimit || name.size() > 0xffff)
            throw InputError(where + ": zip entry '" + name + "'", "is too large for a zip without zip64 (" +
                                                                     std::to_string(bytes.size()) + " bytes)");
        const uint32_t crc = detail::crc32_of(bytes);
        // The fields the local header and the directory entry share, from "version needed" on.
        std::string common;
        for (const uint16_t field : {kVersion, uint16_t{0}, uint16_t{0}, uint16_t{0}, kDosDate})
            detail::store_little_endian(common, field);  // version needed, flags, method (stored), time, date
        for (const uint32_t field : {crc, uint32_t(bytes.size()), uint32_t(bytes.size())})
            detail::store_little_endian(common, field);  // CRC, compressed and uncompressed sizes
        detail::store_little_endian(common, uint16_t(name.size()));
        detail::store_little_endian(common, uint16_t{0});  // extra field length

        detail::store_little_endian(archive, uint32_t{0x04034b50});
        archive += common;
        archive += name;
        archive += bytes;

        detail::store_little_endian(directory, uint32_t{0x02014b50});
        detail::store_little_endian(directory, kVersion);  // version made by (MS-DOS attributes)
        directory += common;
        for (const uint16_t field : {uint16_t{0}, uint16_t{0}, uint16_t{0}})
            detail::store_little_endian(directory, field);  // comment length, disk, internal attributes
        detail::store_little_endian(directory, uint32_t{0});  // external attributes
        detail::store_little_endian(directory, uint32_t(offset));
        directory += name;
    }
    const uint64_t directory_offset = archive.size();
    if (directory_offset + directory.size() >= kLimit)
        throw InputError(where, "is too large for a zip without zip64 (" + std::to_string(directory_offset) + " bytes)");
    archive += directory;
    detail::store_little_endian(archive, uint32_t{0x06054b50});
    for (const uint16_t field : {uint16_t{0}, uint16_t{0}, uint16_t(files.size()), uint16_t(files.size())})
        detail::store_little_endian(archive, field);  // this disk, the directory's disk, entries here, in all
    detail::store_little_endian(archive, uint32_t(directory.size()));
    detail::store_little_endian(archive, uint32_t(directory_offset));
    detail::store_little_endian(archive, uint16_t{0});  // comment length
    return archive;
}

}  // namespace vksplat::io::zip
