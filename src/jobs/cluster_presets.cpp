#include <algorithm>
#include <cstdio>
#include <string>

#include "vksplat/cluster/centrality.hpp"
#include "vksplat/error.hpp"
#include "vksplat/jobs/cluster_prune.hpp"

namespace vksplat::jobs {

std::string_view to_string(ClusterPreset preset) {
    switch (preset) {
        case ClusterPreset::whole_picture: return "whole-picture";
        case ClusterPreset::keep_subject: return "keep-subject";
        case ClusterPreset::original: return "original";
    }
    return "?";
}

ClusterPreset parse_cluster_preset(std::string_view name) {
    for (auto preset : {ClusterPreset::whole_picture, ClusterPreset::keep_subject, ClusterPreset::original})
        if (name == to_string(preset)) return preset;
    throw InputError("--preset " + std::string(name), "unknown; choose whole-picture, keep-subject or original");
}

void apply_cluster_preset(ClusterPreset preset, ClusterOptions& options) {
    const ClusterOptions defaults;
    options.weights = defaults.weights;
    options.selection = defaults.selection;
    switch (preset) {
        case ClusterPreset::whole_picture: break;
        case ClusterPreset::keep_subject:
            options.weights.lambda = 1.0;
            options.selection.ratio = 0.8;
            options.selection.max_contribution_loss = 1.0;
            break;
        case ClusterPreset::original:
            options.weights = cluster::kOriginalWeights;
            options.selection.ratio = 0.9;
            options.selection.ratio_of = cluster::RatioOf::clusters;
            options.selection.max_contribution_loss = 1.0;
            break;
    }
}

ClusterPresetChoice choose_cluster_preset(const GaussianCloud& cloud, const std::vector<Camera>& cameras,
                                          const ClusterOptions& options) {
    std::vector<Camera> views;
    for (size_t view : region_views(cameras, options)) views.push_back(cameras[view]);
    const std::vector<float> centrality = cluster::view_centrality(cloud.positions, views);
    ClusterPresetChoice choice;
    choice.gaussians = centrality.size();
    choice.views = views.size();
    choice.central_threshold = options.weights.central_threshold;
    choice.room = size_t(std::count_if(centrality.begin(), centrality.end(),
                                       [&](float c) { return c < choice.central_threshold; }));
    if (choice.room_share() >= kKeepSubjectFromRoomShare) choice.preset = ClusterPreset::keep_subject;
    return choice;
}

std::string describe(const ClusterPresetChoice& choice) {
    char line[320];
    std::snprintf(line, sizeof(line),
                  "preset: %s (automatic: %.1f%% of the %zu Gaussians are room, centrality under %.3g in the %zu "
                  "views; keep-subject from %.0f%%)",
                  std::string(to_string(choice.preset)).c_str(), 100.0 * choice.room_share(), choice.gaussians,
                  choice.central_threshold, choice.views, 100.0 * kKeepSubjectFromRoomShare);
    return line;
}

}  // namespace vksplat::jobs
