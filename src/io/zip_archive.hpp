#pragma once
// Zip archives: read as torch.save and splat-transform write them (for the gsplat checkpoint and
// SOG readers): the central directory (zip64 sizes and offsets included), stored and deflated
// entries, each checked against its CRC. Entries are read on demand, so a large archive costs only
// what is asked. Written with every entry stored (for SOG, whose WebP textures are compressed already).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace vksplat::io::zip {

struct Entry {
    std::string name;
    uint16_t method = 0;
    uint32_t crc = 0;
    uint64_t compressed_size = 0;
    uint64_t size = 0;
    uint64_t local_offset = 0;
};

class Archive {
public:
    // Opens `path` and reads its directory; every error is an InputError naming `where`.
    Archive(const std::filesystem::path& path, std::string where);

    const std::vector<Entry>& entries() const { return entries_; }
    // The entry called `name`, or null.
    const Entry* find(const std::string& name) const;
    // The entry's bytes, inflated if deflated, checked against its size and CRC.
    std::string read(const Entry& entry);

private:
    std::string bytes_at(uint64_t offset, uint64_t count, const std::string& at);
    void read_directory();

    std::string where_;
    std::ifstream in_;
    uint64_t file_size_ = 0;
    std::vector<Entry> entries_;
};

// A zip archive of `files` (name, bytes) in the order given, each stored uncompressed, dated
// 1980-01-01 so that the same files make the same archive. Throws InputError naming `where` if
// the archive would need zip64 (an entry, or the whole, of 4 GiB or more; 65535 entries or more).
std::string stored_archive(const std::vector<std::pair<std::string, std::string>>& files, const std::string& where);

}  // namespace vksplat::io::zip
