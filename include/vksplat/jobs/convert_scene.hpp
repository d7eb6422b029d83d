#pragma once
// Converts a scene file from one format to another (see io/formats.hpp for the formats): what
// `vksplat convert` does.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <optional>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/prune/sh_precision.hpp"

namespace vksplat::jobs {

struct ConvertOptions {
    std::string input_format;   // empty: by the input's extension (and header, for .ply)
    std::string output_format;  // empty: by the output's extension, never by what a file there holds
    io::WriteMode mode = io::WriteMode::refuse_existing;
    // The higher SH rounded to this precision before writing (prune/sh_precision.hpp: a smaller SPZ).
    std::optional<prune::ShPrecision> sh_precision = std::nullopt;
};

struct ConvertResult {
    std::string input_format, output_format;
    size_t gaussians = 0;
    int input_sh_degree = 0;
    int output_sh_degree = 0;        // what the output format kept (.splat keeps only the DC term)
    std::vector<std::string> notes;  // the reader's notes, then what the output format loses
};

// Reads `input` and writes it to `output`. Both formats are resolved, and an existing output is
// refused (unless options.mode is overwrite), as is an output that is the input (always), before
// the input is read, so a mistake costs no time on a large scene. Throws InputError naming the
// file at fault.
ConvertResult convert_scene(const std::filesystem::path& input, const std::filesystem::path& output,
                            const ConvertOptions& options = {});

}  // namespace vksplat::jobs
