#include "vksplat/jobs/view_selection.hpp"

#include <charconv>
#include <numeric>

#include "vksplat/error.hpp"

namespace vksplat::jobs {
namespace {

size_t parse_index(const std::string& text, const std::string& whole) {
    size_t value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end)
        throw InputError("view list '" + whole + "'", "'" + text + "' is not a view index");
    return value;
}

}  // namespace

std::vector<size_t> parse_view_list(const std::string& text, size_t count) {
    std::vector<size_t> views;
    if (text.empty() || text == "all") {
        views.resize(count);
        std::iota(views.begin(), views.end(), size_t{0});
        return views;
    }
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        const size_t dash = item.find('-');
        const size_t first = parse_index(item.substr(0, dash), text);
        const size_t last = dash == std::string::npos ? first : parse_index(item.substr(dash + 1), text);
        if (last < first) throw InputError("view list '" + text + "'", "range '" + item + "' runs backwards");
        if (last >= count)
            throw InputError("view list '" + text + "'", "view " + std::to_string(last) + " does not exist (there are " +
                                                             std::to_string(count) + " cameras)");
        for (size_t v = first; v <= last; ++v) views.push_back(v);
        start = comma + 1;
    }
    return views;
}

}  // namespace vksplat::jobs
