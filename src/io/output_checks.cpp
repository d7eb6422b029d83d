// The checks every output passes before a command starts work: it may be written, and it is not
// one of the command's own inputs.
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "io/output_checks.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io {
namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code error;
    if (fs::exists(a, error) && fs::exists(b, error)) return fs::equivalent(a, b, error) && !error;
    return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error);
}

void check_destination(const fs::path& path, WriteMode mode) {
    std::error_code error;
    if (fs::is_directory(path, error)) throw InputError(path.string(), "is a folder; a file name is needed");
    if (mode == WriteMode::refuse_existing && fs::exists(path, error))
        throw InputError(path.string(), "already exists; not overwritten (--force replaces it)");
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(folder, error))
        throw InputError(path.string(), "cannot be written: folder " + folder.string() + " does not exist");
}

void check_writable(const fs::path& path, WriteMode mode) {
    check_destination(path, mode);
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    // A file made and removed again: the only answer that holds for root, ACLs, read-only mounts
    // and file systems that refuse new files (access() says yes to root in /sys).
    std::string probe = (folder / ".vksplat-write-probe-XXXXXX").string();
    const int descriptor = ::mkstemp(probe.data());
    if (descriptor < 0)
        throw InputError(path.string(), "cannot be written: folder " + folder.string() + ": " + std::strerror(errno));
    ::close(descriptor);
    ::unlink(probe.c_str());
}

void refuse_input_as_output(const fs::path& output, const std::vector<fs::path>& inputs) {
    for (const auto& input : inputs)
        if (!input.empty() && same_file(output, input))
            throw InputError(output.string(), "is an input of this command" +
                                                  (input == output ? std::string() : " (" + input.string() + ")") +
                                                  "; writing over an input is refused, --force or not");
}

}  // namespace vksplat::io
