// vksplat info: what a scene file holds, and what sanitising it would change.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "commands.hpp"
#include "vksplat/io/formats.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::cli {
namespace {

double quantile(std::vector<float> values, double q) {
    if (values.empty()) return 0;
    const size_t k = std::min(values.size() - 1, size_t(q * double(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + long(k), values.end());
    return values[k];
}

int run_info(const std::string& path) {
    std::vector<std::string> notes;
    GaussianCloud cloud = io::read_scene(path, &notes);
    std::printf("%s\n  Gaussians: %zu\n  SH degree: %d\n  file: %ju bytes\n", path.c_str(), cloud.size(),
                cloud.sh_degree, uintmax_t(std::filesystem::file_size(path)));
    for (const auto& note : notes) std::printf("  note: %s\n", note.c_str());

    const SanitizeReport report = sanitize(cloud);
    std::printf("  sanitise: %s\n", report.summary().c_str());
    if (cloud.empty()) return 0;

    for (int axis = 0; axis < 3; ++axis) {
        std::vector<float> coords(cloud.size());
        for (size_t i = 0; i < cloud.size(); ++i) coords[i] = cloud.positions[3 * i + axis];
        std::printf("  %c: 1%% %.3f, median %.3f, 99%% %.3f\n", "xyz"[axis], quantile(coords, 0.01),
                    quantile(coords, 0.5), quantile(coords, 0.99));
    }
    std::vector<float> opacity(cloud.size()), scale(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) {
        opacity[i] = 1.0f / (1.0f + std::exp(-cloud.opacity_logits[i]));
        scale[i] = std::exp(std::max({cloud.log_scales[3 * i], cloud.log_scales[3 * i + 1], cloud.log_scales[3 * i + 2]}));
    }
    std::printf("  opacity: 10%% %.3f, median %.3f, 90%% %.3f\n", quantile(opacity, 0.1), quantile(opacity, 0.5),
                quantile(opacity, 0.9));
    std::printf("  largest scale: median %.4g, 99%% %.4g, max %.4g\n", quantile(scale, 0.5), quantile(scale, 0.99),
                quantile(scale, 1.0));
    return 0;
}

}  // namespace

void register_info(CLI::App& app, Action& action) {
    auto* command = app.add_subcommand("info", "describe a scene file and what sanitising would fix");
    command->footer("Example:\n  vksplat info point_cloud.ply");
    auto path = std::make_shared<std::string>();
    command->add_option("scene", *path, "scene file (any format vksplat reads)")->required()->check(CLI::ExistingFile);
    command->callback([&action, path] { action = [path] { return run_info(*path); }; });
}

}  // namespace vksplat::cli
