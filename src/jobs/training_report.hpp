#pragma once
// report.html of a training run: how the Gaussian count and (where measured) the test PSNR went
// over the iterations, and test PSNR against the count, with the run's numbers in a table. Written
// beside point_cloud.ply by train_scene.
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/io/write_mode.hpp"
#include "vksplat/jobs/train_scene.hpp"

namespace vksplat::jobs {

// The files the report writes into `folder` (checked before a run, written after it).
std::vector<std::filesystem::path> training_report_files(const std::filesystem::path& folder);

void write_training_report(const std::filesystem::path& folder, const TrainResult& result, const std::string& data,
                           io::WriteMode mode);

}  // namespace vksplat::jobs
