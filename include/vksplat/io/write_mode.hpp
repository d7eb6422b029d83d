#pragma once
// How every writer in io treats an existing file, and the one routine they all write through,
// so that no writer ever leaves a half-written file behind or replaces a file by accident.
#include <filesystem>
#include <functional>
#include <ostream>
#include <vector>

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

// What write_file_atomically would refuse, for commands to call before any work, so that minutes
// of work never end in a refusal: throws InputError naming `path` if it exists and mode is
// refuse_existing, if it is a folder, or if its folder is missing or takes no new file (tried by
// making and removing one).
void check_writable(const std::filesystem::path& path, WriteMode mode);

// Whether two paths name one file: the same inode where both exist (links, "./a" and "a"), else
// the same path once made absolute and normalised (an output that does not exist yet).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws InputError naming `output` if it is one of `inputs` (the same file by any path or link):
// no command writes over what it reads, whatever the WriteMode.
void refuse_input_as_output(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs);

}  // namespace vksplat::io
