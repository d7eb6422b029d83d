#pragma once
// For tests that read the files they wrote (CSV, HTML, SVG) as text.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace vksplat::test {

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// How many times `needle` occurs in `haystack`, overlapping occurrences included.
inline size_t count(const std::string& haystack, const std::string& needle) {
    size_t n = 0;
    for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
    return n;
}

}  // namespace vksplat::test
