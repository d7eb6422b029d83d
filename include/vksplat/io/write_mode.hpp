#pragma once
// How every writer in io treats an existing file, and the one routine they all write through,
// so that no writer ever leaves a half-written file behind or replaces a file by accident.
#include <filesystem>
#include <functional>
#include <ostream>

namespace vksplat::io {

enum class WriteMode {
    refuse_existing,  // throw InputError if the destination exists (the default everywhere)
    overwrite,        // replace the destination
};

// Writes `path` through `write`: the bytes go to a temporary file in the same folder, which is
// renamed onto `path` only once `write` has returned and the stream reported no error. If anything
// fails, the temporary file is removed and the destination is left as it was. Throws InputError
// naming `path` if it exists and mode is refuse_existing, or if writing fails.
void write_file_atomically(const std::filesystem::path& path, WriteMode mode,
                           const std::function<void(std::ostream&)>& write);

}  // namespace vksplat::io
