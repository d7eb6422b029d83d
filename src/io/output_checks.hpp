#pragma once
// What check_writable (vksplat/io/write_mode.hpp) checks short of making a file: for
// write_file_atomically, whose own temporary file is the test that the folder takes files.
#include <filesystem>

#include "vksplat/io/write_mode.hpp"

namespace vksplat::io {

// Throws InputError naming `path` if it is a folder, exists while mode is refuse_existing, or its
// folder does not exist.
void check_destination(const std::filesystem::path& path, WriteMode mode);

}  // namespace vksplat::io
