#pragma once
// Shared by the report tests, which read the HTML and SVG they write as text.
#include <string>

namespace vksplat::report {

// How many times `needle` occurs in `haystack`, overlapping occurrences included.
inline size_t count(const std::string& haystack, const std::string& needle) {
    size_t n = 0;
    for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
    return n;
}

}  // namespace vksplat::report
