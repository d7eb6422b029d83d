#include <string>

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

}  // namespace vksplat::jobs
