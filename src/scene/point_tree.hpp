#pragma once
// A nanoflann KD-tree over xyz triples held elsewhere (no copy): the one adaptor the cluster
// neighbour search and the trainer's initial scales (mean distance to the nearest SfM points) share.
#include <cstddef>
#include <cstdint>
#include <span>

#include <nanoflann.hpp>

namespace vksplat {

struct PointSpan {
    std::span<const float> xyz;
    size_t kdtree_get_point_count() const { return xyz.size() / 3; }
    float kdtree_get_pt(size_t index, size_t dim) const { return xyz[index * 3 + dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;  // nanoflann computes the box itself
    }
};

using PointTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointSpan>, PointSpan, 3, uint32_t>;

}  // namespace vksplat
