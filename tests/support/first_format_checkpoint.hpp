#pragma once
// The header of the first checkpoint format (VKSCKPT1: magic, then count, SH degree, iteration
// and skipped steps), which recorded neither its run nor the densification sums. Its arrays are
// left out: such a checkpoint is refused before they would be read.
#include <cstdint>
#include <filesystem>
#include <fstream>

namespace vksplat::test {

inline void write_first_format_checkpoint(const std::filesystem::path& path, uint64_t count, uint64_t iteration) {
    std::ofstream out(path, std::ios::binary);
    out << "VKSCKPT1";
    for (uint64_t value : {count, uint64_t(1), iteration, uint64_t(0)})
        out.write(reinterpret_cast<const char*>(&value), sizeof(value));
}

}  // namespace vksplat::test
