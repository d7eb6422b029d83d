#include "vksplat/jobs/view_selection.hpp"

#include <algorithm>
#include <charconv>
#include <numeric>

#include "vksplat/error.hpp"

namespace vksplat::jobs {
namespace {

// INRIA's trainer holds out the first 13 cameras of its test set.
constexpr size_t kInriaTestViews = 13;

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

std::vector<size_t> default_test_views(const std::vector<Camera>& cameras) {
    const bool split = !cameras.empty() && std::none_of(cameras.begin(), cameras.end(),
                                                        [](const Camera& c) { return c.split.empty(); });
    if (split) {
        std::vector<size_t> views;
        for (size_t i = 0; i < cameras.size(); ++i)
            if (cameras[i].split == "test") views.push_back(i);
        return views;
    }
    const size_t camera_count = cameras.size();
    std::vector<size_t> views(camera_count > kInriaTestViews ? kInriaTestViews : camera_count);
    for (size_t i = 0; i < views.size(); ++i) views[i] = i;
    return views;
}

std::vector<size_t> default_train_views(size_t camera_count, const std::vector<size_t>& test_views) {
    std::vector<size_t> views;
    for (size_t i = 0; i < camera_count; ++i)
        if (std::find(test_views.begin(), test_views.end(), i) == test_views.end()) views.push_back(i);
    if (views.empty())
        for (size_t i = 0; i < camera_count; ++i) views.push_back(i);
    return views;
}

void check_view_indices(const std::vector<size_t>& views, size_t camera_count) {
    for (size_t view : views)
        if (view >= camera_count)
            throw InputError("view " + std::to_string(view), "there are only " + std::to_string(camera_count) + " cameras");
}

bool views_held_out(const std::vector<size_t>& test, const std::vector<size_t>& train) {
    return std::none_of(test.begin(), test.end(),
                        [&](size_t view) { return std::find(train.begin(), train.end(), view) != train.end(); });
}

ViewSplit split_views(const std::vector<Camera>& cameras, const std::vector<size_t>& test,
                      const std::vector<size_t>& train) {
    ViewSplit split;
    split.test = test.empty() ? default_test_views(cameras) : test;
    split.train = train.empty() ? default_train_views(cameras.size(), split.test) : train;
    check_view_indices(split.test, cameras.size());
    check_view_indices(split.train, cameras.size());
    split.held_out = views_held_out(split.test, split.train);
    return split;
}

}  // namespace vksplat::jobs
