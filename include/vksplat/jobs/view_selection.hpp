#pragma once
// Parsing of view lists such as "0,3,5-7".
#include <cstddef>
#include <string>
#include <vector>

namespace vksplat::jobs {

// Indices named by `text` ("0,3,5-7"), in the order given, each < count. Empty text or "all"
// selects every view. Throws InputError for malformed text or an index out of range.
std::vector<size_t> parse_view_list(const std::string& text, size_t count);

}  // namespace vksplat::jobs
