// The options of cluster pruning's stages 1-6 (see cluster_options.hpp).
#include "cluster_options.hpp"

#include "number_checks.hpp"
#include "vksplat/error.hpp"
#include "vksplat/jobs/view_selection.hpp"

namespace vksplat::cli {
namespace {

void add_regions(CLI::App& c, ClusterStageArgs& a) {
    auto& o = a.options;
    c.add_option("--max-views", o.max_views, "render at most this many training views, evenly spread")
        ->check(count_in(1));
    c.add_option("--render-views", a.render_views, "views to render, e.g. 13-99 (default: the training views)");
    c.add_option("--resolution-scale", o.resolution_scale, "render and segment at this fraction of the camera size")
        ->check(positive_number(4.0));
    c.add_option("--seg-sigma", o.segmentation.sigma, "graph segmentation: pre-smoothing in pixels")
        ->check(number_in(0.0));
    c.add_option("--seg-k", o.segmentation.k, "graph segmentation: scale (larger: larger regions)")
        ->check(positive_number());
    c.add_option("--seg-min-size", o.segmentation.min_size_fraction, "smallest region, as a fraction of the image")
        ->check(number_in(0.0, 1.0));
    c.add_option("--min-alpha", o.segmentation.min_alpha, "pixels with rendered alpha below this carry no region")
        ->check(number_in(0.0, 1.0));
}

void add_project(CLI::App& c, ClusterStageArgs& a) {
    auto& o = a.options;
    c.add_option("--views", a.keep_views, "use exactly these views instead of the view filter's choice");
    c.add_option("--max-largest-fraction", o.filter.max_largest_fraction, "filter: largest region's share at most")
        ->check(number_in(0.0, 1.0));
    c.add_option("--max-regions", o.filter.max_regions, "filter: regions per view at most")->check(count_in(1));
    c.add_option("--min-edge-alignment", o.filter.min_edge_alignment, "filter: border/image gradient ratio at least")
        ->check(number_in(0.0));
    c.add_option("--min-labelled-fraction", o.filter.min_labelled_fraction, "filter: share of pixels in a region")
        ->check(number_in(0.0, 1.0));
    c.add_option("--occlusion", a.occlusion, "occlusion rule: depth (nearest centre) or blend (alpha*T at centre)")
        ->check(CLI::IsMember({"depth", "blend"}));
    c.add_option("--min-weight", o.projection.min_weight, "blend rule: smallest alpha*T at the centre that counts")
        ->check(number_in(0.0, 1.0));
}

void add_build(CLI::App& c, ClusterStageArgs& a) {
    auto& o = a.options;
    c.add_option("--delta-dist", a.delta, "neighbour radius in scene units, or auto");
    c.add_option("--max-neighbours", o.max_neighbours, "nearest neighbours per Gaussian within the radius")
        ->check(count_in(1));
    c.add_option("--semantic-tol", o.merge.semantic_tol, "largest share of common views whose regions may differ")
        ->check(number_in(0.0, 1.0));
    c.add_option("--min-common-views", o.merge.min_common_views, "views that must see both of a pair")
        ->check(count_in(1));
}

void add_score(CLI::App& c, ClusterStageArgs& a) {
    auto& w = a.options.weights;
    c.add_option("--alpha", w.alpha, "weight of the spatial variance in G* (the issue's: 0.1)")
        ->capture_default_str()
        ->check(number_in());
    c.add_option("--beta", w.beta, "weight of the depth variance in G* (the issue's: 0.1)")
        ->capture_default_str()
        ->check(number_in());
    c.add_option("--gamma", w.gamma, "weight of the multi-view visibility ratio in G* (the issue's: 1)")
        ->capture_default_str()
        ->check(number_in());
    c.add_option("--mvr-mean-frac-weight", w.mvr_mean_frac_weight, "share of mean_visible_frac in MVR")
        ->capture_default_str()
        ->check(number_in(0.0, 1.0));
    c.add_option("--kappa", w.kappa,
                 "weight of the contribution (largest share of the picture a member paints) in G* (the issue's: 0)")
        ->capture_default_str()
        ->check(number_in());
    c.add_option("--lambda", w.lambda,
                 "weight in G* of being central: how much the views look at the cluster reaches --central-threshold")
        ->capture_default_str()
        ->check(number_in());
    c.add_option("--central-threshold", w.central_threshold,
                 "centrality (mean over views of 1 - rho^2 at the projected centre) from which a cluster is central")
        ->check(number_in(0.0, 1.0))
        ->capture_default_str();
}

}  // namespace

void add_cluster_stage_options(CLI::App& command, ClusterStageArgs& args, unsigned stages) {
    if (stages & kRegions) add_regions(command, args);
    if (stages & kProject) add_project(command, args);
    if (stages & kBuild) add_build(command, args);
    if (stages & kScore) add_score(command, args);
}

void resolve_cluster_stage_args(ClusterStageArgs& args, size_t camera_count) {
    auto& options = args.options;
    if (!args.render_views.empty()) options.views = jobs::parse_view_list(args.render_views, camera_count);
    if (!args.keep_views.empty()) options.keep_views = jobs::parse_view_list(args.keep_views, camera_count);
    options.projection.rule = cluster::parse_occlusion_rule(args.occlusion);
    if (args.delta == "auto") {
        options.delta.reset();
        return;
    }
    options.delta = finite_number(args.delta);
    if (!options.delta) throw InputError("--delta-dist " + args.delta, "expected a distance or auto");
    if (*options.delta <= 0) throw InputError("--delta-dist " + args.delta, "a distance must be above 0");
}

}  // namespace vksplat::cli
