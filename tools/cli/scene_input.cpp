// Reading the scene a command works on; in its own file so that the GPU-host benchmark binary,
// which registers only `bench`, links it without the rest of the CLI.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::cli {

GaussianCloud read_scene_file(const std::string& path) {
    std::vector<std::string> notes;
    GaussianCloud cloud = io::read_scene(path, &notes);
    for (const auto& note : notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    return cloud;
}

}  // namespace vksplat::cli
