// The checks every output passes before a command starts work: it may be written, and it is not
// one of the command's own inputs.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "vksplat/error.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

// Two paths name one file: the same inode where both exist (links, "./a" and "a"), else the same
// path once made absolute and normalised (an output that does not exist yet).
bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error) && !error;
    return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error);
}

}  // namespace

void check_writable(const fs::path& path, WriteMode mode) {
    std::error_code error;
    if (fs::is_directory(path, error)) throw InputError(path.string(), "is a folder; a file name is needed");
    if (mode == WriteMode::refuse_existing && fs::exists(path, error))
        throw InputError(path.string(), "already exists; not overwritten (--force replaces it)");
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(folder, error))
        throw InputError(path.string(), "cannot be written: folder " + folder.string() + " does not exist");
    // access() rather than the permission bits: it also answers for root, ACLs and read-only mounts.
    if (::access(folder.c_str(), W_OK) != 0)
        throw InputError(path.string(), "cannot be written: folder " + folder.string() + ": " + std::strerror(errno));
}

void refuse_input_as_output(const fs::path& output, const std::vector<fs::path>& inputs) {
    for (const auto& input : inputs)
        if (!input.empty() && same_file(output, input))
            throw InputError(output.string(), "is an input of this command (" + input.string() +
                                                  "); writing over an input is refused, --force or not");
}

}  // namespace vksplat::io
