#pragma once
// One entry per reader that a fuzzer drives: the bytes become a file (the readers take paths) in a
// scratch folder of this process, and the reader reads it. Shared by the libFuzzer binaries
// (fuzz_main.cpp, built with -DVKSPLAT_FUZZ=ON) and by the regression test that replays every seed
// and every input that once crashed (fuzz_regressions_test.cpp, built with the normal suite), so both
// drive the readers the same way.
//
// A reader may succeed or throw InputError; anything else it does (another exception, a crash, a
// hang, an allocation far beyond the input's size) is a bug.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "io/colmap_model.hpp"
#include "vksplat/io/cameras.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/io/npy.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::fuzz {

// A COLMAP input holds cameras.* then this line then images.* (tests/fuzz/make_seeds.py writes them so).
inline constexpr std::string_view kSplitMarker = "\n#VKSPLAT-FUZZ-SPLIT#\n";

// A folder under /tmp named after this process, removed when the process ends.
class ScratchFolder {
public:
    ScratchFolder()
        : path_(std::filesystem::temp_directory_path() / ("vksplat_fuzz_" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    // Writes `bytes` to `name`, which may include a subfolder.
    std::filesystem::path write(const std::string& name, std::string_view bytes) const {
        const auto path = path_ / name;
        std::filesystem::create_directories(path.parent_path());
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return path;
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline void read_colmap_model(const ScratchFolder& scratch, std::string_view bytes, const std::string& extension) {
    const size_t split = bytes.find(kSplitMarker);
    const std::string_view cameras = bytes.substr(0, split);
    const std::string_view images =
        split == std::string_view::npos ? std::string_view() : bytes.substr(split + kSplitMarker.size());
    // A folder per flavour: one holding both cameras.txt and cameras.bin would be ambiguous.
    const std::string folder = "colmap" + extension + "/";
    scratch.write(folder + "cameras" + extension, cameras);
    scratch.write(folder + "images" + extension, images);
    std::vector<std::string> warnings;
    io::read_colmap_cameras(scratch.path() / ("colmap" + extension), &warnings);
}

struct FuzzTarget {
    const char* name;  // the folder of its seeds and regressions, and the binary's suffix
    void (*read)(const ScratchFolder& scratch, std::string_view bytes);
};

inline const std::vector<FuzzTarget>& fuzz_targets() {
    static const std::vector<FuzzTarget> targets = {
        {"ply", [](const ScratchFolder& s, std::string_view b) { io::read_ply(s.write("in.ply", b)); }},
        {"cameras_json",
         [](const ScratchFolder& s, std::string_view b) { io::read_inria_cameras(s.write("cameras.json", b)); }},
        {"colmap_binary", [](const ScratchFolder& s, std::string_view b) { read_colmap_model(s, b, ".bin"); }},
        {"colmap_text", [](const ScratchFolder& s, std::string_view b) { read_colmap_model(s, b, ".txt"); }},
        {"transforms_json",
         [](const ScratchFolder& s, std::string_view b) { io::read_nerf_transforms(s.write("transforms.json", b)); }},
        {"npy", [](const ScratchFolder& s, std::string_view b) { io::read_npy(s.write("in.npy", b)); }},
        {"splat", [](const ScratchFolder& s, std::string_view b) { io::read_splat(s.write("in.splat", b)); }},
        {"spz", [](const ScratchFolder& s, std::string_view b) { io::read_spz(s.write("in.spz", b)); }},
        {"compressed_ply",
         [](const ScratchFolder& s, std::string_view b) { io::read_compressed_ply(s.write("in.ply", b)); }},
        {"gsplat_pt",
         [](const ScratchFolder& s, std::string_view b) { io::read_gsplat_checkpoint(s.write("in.pt", b)); }},
    };
    return targets;
}

inline const FuzzTarget* find_fuzz_target(std::string_view name) {
    for (const auto& target : fuzz_targets())
        if (name == target.name) return &target;
    return nullptr;
}

}  // namespace vksplat::fuzz
