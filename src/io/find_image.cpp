// Camera files name photos loosely (INRIA's img_name has no extension, NeRF's file_path may not):
// find_image() resolves such a name to the file in an images folder.
#include <algorithm>

#include "vksplat/error.hpp"
#include "vksplat/io/cameras.hpp"

namespace vksplat::io {

std::filesystem::path find_image(const std::filesystem::path& images_dir, const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path exact = images_dir / name;
    if (fs::is_regular_file(exact)) return exact;
    std::string extensions;
    for (const char* extension : {".png", ".jpg", ".jpeg", ".JPG", ".PNG"}) {
        fs::path candidate = exact;
        candidate += extension;
        if (fs::is_regular_file(candidate)) return candidate;
        extensions += std::string(extensions.empty() ? "" : ", ") + extension;
    }

    // The name may carry another extension than the photo's (e.g. a .jpg renamed .png).
    const fs::path folder = exact.parent_path();
    const fs::path stem = exact.stem();
    std::vector<fs::path> matches;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error))
        if (entry.is_regular_file() && entry.path().stem() == stem) matches.push_back(entry.path());
    if (matches.size() == 1) return matches.front();
    std::sort(matches.begin(), matches.end());
    std::string problem = "no image for camera '" + name + "': tried " + exact.string() + ", that name + " +
                          extensions + ", and any file in " + folder.string() + " with stem '" + stem.string() + "'";
    if (matches.size() > 1) {
        problem += ", which matches several files:";
        for (const auto& match : matches) {
            problem += ' ';
            problem += match.filename().string();
        }
    }
    throw InputError(images_dir.string(), problem);
}

}  // namespace vksplat::io
