#pragma once
// Region maps: per view, which region (a segment of the picture, e.g. one part of the object)
// each pixel belongs to. They are the semantic evidence of cluster pruning: two Gaussians whose
// centres fall in the same region in the views that see both may belong to one cluster.
//
// Stored as .npy int32 [H, W] (-1: no region), so Python users can inspect them with numpy.load.
// Region maps made elsewhere (e.g. by SAM) are read from int32 .npy, from a stack of boolean masks
// (.npy uint8 [K, H, W]) or from a 16-bit (or 8-bit) PNG label image whose 0 means "no region".
#include <cstdint>
#include <filesystem>
#include <vector>

#include "vksplat/io/write_mode.hpp"

namespace vksplat::cluster {

inline constexpr int32_t kNoRegion = -1;

struct RegionMap {
    int width = 0;
    int height = 0;
    std::vector<int32_t> labels;  // row-major, width * height; kNoRegion or a region id >= 0

    int32_t at(int x, int y) const { return labels[size_t(y) * width + x]; }
    // Number of distinct ids >= 0.
    size_t region_count() const;
    // Pixels that carry a region.
    size_t labelled_pixels() const;
};

// Renumbers the regions 0..n-1 in order of first appearance (row-major), keeping kNoRegion, so
// that ids stay small whatever produced them.
void compact_ids(RegionMap& map);

// Paints binary masks (each width * height, non-zero = inside) into one map, largest first, so
// that where masks overlap the smaller one wins (a part inside a whole keeps its own id). Mask k
// gets id k before compaction; pixels in no mask get kNoRegion. Throws InputError if the masks
// have different sizes.
RegionMap combine_masks(const std::vector<std::vector<uint8_t>>& masks, int width, int height);

// Reads a region map in any of the forms above; ids are compacted. Throws InputError naming the
// file for anything else (other dtypes or shapes, an unreadable image).
RegionMap read_region_map(const std::filesystem::path& path);
// Writes int32 [H, W] .npy.
void write_region_map(const std::filesystem::path& path, const RegionMap& map,
                      io::WriteMode mode = io::WriteMode::refuse_existing);

}  // namespace vksplat::cluster
