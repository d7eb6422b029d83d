#include "vksplat/io/output_folders.hpp"

#include <system_error>

#include "vksplat/error.hpp"

namespace vksplat::io {

namespace fs = std::filesystem;

OutputFolders::~OutputFolders() {
    for (auto folder = made_.rbegin(); folder != made_.rend(); ++folder) {
        std::error_code error;
        if (fs::is_directory(*folder, error) && fs::is_empty(*folder, error)) fs::remove(*folder, error);
    }
}

void OutputFolders::create(const fs::path& folder) {
    std::vector<fs::path> missing;
    std::error_code error;
    for (fs::path at = fs::absolute(folder, error); !at.empty() && !fs::exists(at, error); at = at.parent_path()) {
        missing.push_back(at);
        if (at == at.parent_path()) break;
    }
    // Remembered first: where only some can be made, those are removed again too.
    made_.insert(made_.end(), missing.rbegin(), missing.rend());
    fs::create_directories(folder, error);
    if (error) throw InputError(folder.string(), "cannot be made: " + error.message());
}

}  // namespace vksplat::io
