#version 460
// Adds one view's per-Gaussian statistics into the totals over views (shaders/render/stats_totals.h).
// One invocation per Gaussian owns its totals, so plain adds suffice and the sums are exact.
#extension GL_GOOGLE_include_directive : require
#define GATHER_STATS 1
#include "shaders/render/stats_totals.h"

layout(local_size_x = 256) in;

layout(push_constant) uniform Push { StatsTotalsPush pc; };

void main() {
    if (pc.view.counters.v[COUNTER_ENTRIES_NEEDED] > pc.entry_capacity) return;
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x) {
        const uint64_t weight = pc.view.stat_weight.v[i];
        const uint64_t low = pc.sums.weight_low.v[i] + weight;
        if (low < weight) pc.sums.weight_high.v[i] += 1u;
        pc.sums.weight_low.v[i] = low;
        pc.sums.max_weight.v[i] = max(pc.sums.max_weight.v[i], pc.view.stat_max_weight.v[i]);
        pc.sums.pixels.v[i] += uint64_t(pc.view.stat_pixels.v[i]);
        const float radius = pc.view.means_depth.v[i].w;
        if (radius > 0.0) {
            const uint64_t r = uint64_t(min(radius, float(TOTALS_MAX_RADIUS)));
            pc.sums.radius_squared.v[i] += r * r;
            pc.sums.views_visible.v[i] += 1u;
        }
    }
}
