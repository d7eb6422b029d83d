#pragma once
// Which region maps are worth using: a map is dropped when one region covers most of what is
// labelled (no parts to tell apart), when it holds thousands of regions (noise), when almost no
// pixel carries a region (no subject in view), or when its region borders ignore the picture's
// edges (the regions are not of this picture).
#include <cstddef>
#include <string>
#include <vector>

#include "vksplat/cluster/region_map.hpp"

namespace vksplat::cluster {

struct ViewFilterParams {
    double min_labelled_fraction = 0.02;  // of the image
    double max_largest_fraction = 0.9;    // of the labelled pixels, for the largest region
    size_t max_regions = 1000;
    // Mean gradient magnitude of the render on region borders over its mean on labelled pixels
    // (both off the subject's outline). Borders drawn along edges score well above 1; borders of
    // random labels score about 1. A map whose regions never touch is not judged by it.
    double min_edge_alignment = 1.5;
};

struct ViewQuality {
    double labelled_fraction = 0;   // pixels with a region / all pixels
    double largest_fraction = 0;    // largest region / labelled pixels
    size_t regions = 0;
    size_t border_pixels = 0;       // labelled pixels next to a different region (off the outline)
    double edge_alignment = 0;      // 0 when there are no borders
    bool keep = false;
    std::string reason;             // why it was dropped; empty when kept
};

// rgb: the render the map belongs to (3 floats per pixel, the map's size).
// Throws std::invalid_argument when the sizes disagree.
ViewQuality assess_view(const RegionMap& map, const std::vector<float>& rgb, const ViewFilterParams& params = {});

}  // namespace vksplat::cluster
