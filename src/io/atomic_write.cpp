// Writes through a temporary file in the destination's folder, then renames it into place: a rename
// within one file system is atomic, so readers see either the old file or the complete new one.
#include "vksplat/io/write_mode.hpp"

#include <fstream>
#include <random>
#include <system_error>

#include "io/output_checks.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

// A name beside `path` that no one else is using: hidden, and random so that two writers of the
// same destination never share a temporary file.
fs::path temporary_sibling(const fs::path& path) {
    std::random_device random;
    const auto tag = (static_cast<unsigned long long>(random()) << 32) ^ random();
    std::string name = ".";
    name += path.filename().string();
    name += '.';
    name += std::to_string(tag);
    name += ".tmp";
    return path.parent_path() / name;
}

// Moves `temporary` onto `path`. Without overwrite, a hard link is made instead of a rename, because
// creating a link fails if the destination appeared meanwhile, where rename would replace it.
void commit(const fs::path& temporary, const fs::path& path, WriteMode mode) {
    std::error_code error;
    if (mode == WriteMode::refuse_existing) {
        fs::create_hard_link(temporary, path, error);
        if (!error) {
            fs::remove(temporary, error);
            return;
        }
        if (error == std::errc::file_exists)
            throw InputError(path.string(), "already exists (appeared while writing); not overwritten (--force replaces it)");
        // File systems without hard links: fall back to a checked rename.
        if (fs::exists(path)) throw InputError(path.string(), "already exists; not overwritten (--force replaces it)");
        error.clear();
    }
    fs::rename(temporary, path, error);
    if (error) throw InputError(path.string(), "cannot be written: " + error.message());
}

}  // namespace

void write_file_atomically(const fs::path& path, WriteMode mode, const std::function<void(std::ostream&)>& write) {
    check_destination(path, mode);  // the temporary file below tests that the folder takes files
    const fs::path temporary = temporary_sibling(path);
    try {
        {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            if (!out) throw InputError(path.string(), "cannot be written: cannot create " + temporary.string());
            write(out);
            out.close();  // closing flushes: a full disk shows up here, not in the destructor
            if (!out) throw InputError(path.string(), "cannot be written: writing failed (disk full?)");
        }
        commit(temporary, path, mode);
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
}

}  // namespace vksplat::io
