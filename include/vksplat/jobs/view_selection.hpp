#pragma once
// Which views a job uses: lists such as "0,3,5-7", and the held-out split.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"

namespace vksplat::jobs {

// Indices named by `text` ("0,3,5-7"), in the order given, each < count. Empty text or "all"
// selects every view. Throws InputError for malformed text or an index out of range.
std::vector<size_t> parse_view_list(const std::string& text, size_t count);

// The held-out views: where every camera names its split (Camera::split), the "test" ones; else
// INRIA's convention, the first 13 cameras when there are more than 13, else every camera (and
// there is no held-out set).
std::vector<size_t> default_test_views(const std::vector<Camera>& cameras);
// Every camera that is not a test view; every camera when that leaves none.
std::vector<size_t> default_train_views(size_t camera_count, const std::vector<size_t>& test_views);
// Throws InputError naming the first index that is not below camera_count.
void check_view_indices(const std::vector<size_t>& views, size_t camera_count);

// The views a job holds out and the views it learns or scores on: `test` and `train` as given,
// each where empty by default_test_views and default_train_views. Both are checked against the
// cameras (check_view_indices).
struct ViewSplit {
    std::vector<size_t> test, train;
    // No test view is also a training view: figures measured on the test views are held out. False
    // where the lists given overlap or the defaults left nothing else to train on (13 cameras or
    // fewer without a split); a job that trains says so before its first step.
    bool held_out = true;
};
// True when no view of `test` is in `train`.
bool views_held_out(const std::vector<size_t>& test, const std::vector<size_t>& train);
// What a training job says before its first step where ViewSplit::held_out is false.
inline constexpr const char* kTestViewsTrainedOnWarning =
    "warning: the test views are also training views (the cameras leave no others), so the figures "
    "measured on them are not held out";
ViewSplit split_views(const std::vector<Camera>& cameras, const std::vector<size_t>& test,
                      const std::vector<size_t>& train);

}  // namespace vksplat::jobs
