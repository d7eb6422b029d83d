#pragma once
// What `train` and `finetune` set up alike before their first step (shared here so that the two
// jobs, which differ in data and strategy, do not differ in how they check and announce).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "vksplat/camera/camera.hpp"
#include "vksplat/jobs/finetune.hpp"

namespace vksplat::jobs {

using Notice = std::function<void(const std::string&)>;

// Every training view's photo, read and checked against its camera (training_photo) before the
// first step: a bad one found late would waste the run.
std::map<size_t, train::Photo> training_photos(const PhotoSource& photos, const std::vector<Camera>& cameras,
                                               const std::vector<size_t>& views, const LossMasks& masks = {});

// train::scene_extent of the training views' cameras; each camera it leaves out is announced.
double training_extent(const std::vector<Camera>& cameras, const std::vector<size_t>& views, const Notice& notice);

}  // namespace vksplat::jobs
