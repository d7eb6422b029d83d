#pragma once
// Zstandard in both directions, for the formats that use it (SPZ version 4): one whole frame at a
// time, through libzstd.
#include <cstdint>
#include <string>
#include <string_view>

namespace vksplat::io::detail {

// Decompresses one zstd frame that must hold exactly `expected` bytes. Memory grows only with data
// the frame really holds, so a header that claims more than the file can give costs nothing.
// Throws InputError naming `where` if the frame is corrupt, ends early or holds more.
std::string zstd_decompress(std::string_view frame, uint64_t expected, const std::string& where);

// One zstd frame of `data` at `level` (libzstd's 1 to 19).
std::string zstd_compress(std::string_view data, int level, const std::string& where);

}  // namespace vksplat::io::detail
