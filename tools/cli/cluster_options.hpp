#pragma once
// The options of cluster pruning's stages 1-6 (regions, project, build, score), shared by
// `vksplat cluster` and the cluster method of `vksplat sweep`, so both spell them the same.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "vksplat/jobs/cluster_prune.hpp"

namespace vksplat::cli {

enum ClusterStage : unsigned { kRegions = 1, kProject = 2, kBuild = 4, kScore = 8, kPrune = 16 };

struct ClusterStageArgs {
    jobs::ClusterOptions options;
    // What CLI11 keeps as text until the cameras are known (resolve_cluster_stage_args).
    std::string render_views, keep_views, occlusion = "depth", delta = "0.01";
};

// Adds to `command` the options of those of `stages` among kRegions, kProject, kBuild, kScore.
void add_cluster_stage_options(CLI::App& command, ClusterStageArgs& args, unsigned stages);

// Parses the text options into args.options: view lists against `camera_count` cameras, the
// occlusion rule, and --delta-dist (a distance or auto). Throws InputError for a bad one.
void resolve_cluster_stage_args(ClusterStageArgs& args, size_t camera_count);

}  // namespace vksplat::cli
