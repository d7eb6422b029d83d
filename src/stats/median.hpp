#pragma once
// The median the robust scales here are built on (camera spreads, distances, step times): the
// element at size / 2 once sorted (the upper one of an even count), 0 for no values.
#include <algorithm>
#include <vector>

namespace vksplat::stats {

inline double median(std::vector<double> values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + long(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace vksplat::stats
