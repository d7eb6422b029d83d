// Which tiles a splat can change. The reference lists a splat in every tile of its 3-sigma
// square; most of those tiles hold no pixel where its alpha reaches 1/255, and every such entry
// costs a sort slot and 256 pixel evaluations. A pixel is only touched where
//     opacity * exp(-0.5 d^T C d) >= 1/255   <=>   d^T C d <= 2 ln(255 opacity)
// (C the conic, d the offset from the centre), so a tile is kept when that ellipse meets it
// and it lies inside the reference's square. Pixels' results are exactly the reference's.
// preprocess counts the tiles and emit_tile_entries lists them with these same functions; the
// `precise` qualifiers keep the compiler from evaluating them differently in the two shaders.
#ifndef VKSPLAT_TILE_CULLING_GLSL
#define VKSPLAT_TILE_CULLING_GLSL

#include "vksplat/constants.hpp"

// d^T C d bound inside which alpha >= 1/255, with a relative margin for float rounding in the
// blend's exp (a tile kept needlessly costs time; a tile lost would change pixels). Negative
// when the opacity itself is below 1/255: such a splat touches nothing.
float touch_bound(float opacity) {
    precise const float bound = 2.0 * log(opacity / MIN_ALPHA);
    return bound * 1.0001 + 1e-4;
}

// Minimum of q(d) = d^T C d over d in [lo, hi] (a box not containing 0), along the edge where
// one coordinate is fixed at `fixed_value`: the quadratic's minimum on that line, clamped.
float edge_minimum(float fixed_value, float lo, float hi, float c_fixed, float c_cross, float c_free) {
    precise const float free_value = clamp(-c_cross * fixed_value / c_free, lo, hi);
    precise const float q =
        c_fixed * fixed_value * fixed_value + 2.0 * c_cross * fixed_value * free_value + c_free * free_value * free_value;
    return q;
}

// True when some point of the box of pixel centres [first, first + size - 1] is within the
// ellipse d^T C d <= bound.
bool ellipse_meets_box(vec2 mean, vec3 conic, float bound, uvec2 first, uvec2 size) {
    // A conic that float rounding left indefinite has no ellipse: keep the whole box.
    if (!(conic.x > 0.0 && conic.z > 0.0 && conic.x * conic.z > conic.y * conic.y)) return true;
    precise const vec2 box_lo = vec2(first) - mean;
    precise const vec2 box_hi = box_lo + vec2(size - 1u);
    if (all(lessThanEqual(box_lo, vec2(0.0))) && all(greaterThanEqual(box_hi, vec2(0.0)))) return true;
    // The centre is outside the box, so the convex quadratic's minimum lies on its boundary.
    float q = edge_minimum(box_lo.x, box_lo.y, box_hi.y, conic.x, conic.y, conic.z);
    q = min(q, edge_minimum(box_hi.x, box_lo.y, box_hi.y, conic.x, conic.y, conic.z));
    q = min(q, edge_minimum(box_lo.y, box_lo.x, box_hi.x, conic.z, conic.y, conic.x));
    q = min(q, edge_minimum(box_hi.y, box_lo.x, box_hi.x, conic.z, conic.y, conic.x));
    return q <= bound;
}

bool ellipse_meets_tile(vec2 mean, vec3 conic, float bound, uvec2 tile) {
    const uvec2 tile_size = uvec2(TILE_WIDTH, TILE_HEIGHT);
    return ellipse_meets_box(mean, conic, bound, tile * tile_size, tile_size);
}

// The tile rectangle [lo, hi) that can hold touched pixels: the reference's 3-sigma rectangle
// cut down to the ellipse's bounding box (half-widths sqrt(bound * cov_xx), sqrt(bound * cov_yy)).
void touched_rect(vec2 mean, vec3 cov, float bound, uvec2 rect_lo, uvec2 rect_hi, out uvec2 lo, out uvec2 hi) {
    const vec2 half_extent = sqrt(max(bound, 0.0) * vec2(cov.x, cov.z));
    const vec2 tile = vec2(TILE_WIDTH, TILE_HEIGHT);
    // Pixel centres sit at integer coordinates: the touched pixels are ceil(m - e) .. floor(m + e).
    const vec2 first = max(ceil(mean - half_extent), vec2(0.0));
    const vec2 last = floor(mean + half_extent);
    lo = max(rect_lo, uvec2(min(first / tile, vec2(rect_hi))));
    hi = min(rect_hi, uvec2(clamp(floor(last / tile) + 1.0, vec2(0.0), vec2(rect_hi))));
}

// The tiles [first, end) of tile row `row` (within [x_lo, x_hi)) that the ellipse meets: the
// same tiles ellipse_meets_tile keeps, found in O(1) per row instead of one test per tile, which
// matters for the few huge splats that span thousands of tiles. The ellipse's part inside the
// row's band of pixel centres is convex, so its x-extent is an interval: the right boundary
// x(dy) = (-b dy + sqrt(D)) / a is concave in dy and peaks at the ellipse's rightmost point, so
// its maximum over the band is at that point's dy clamped into the band (the left likewise).
uvec2 row_tile_span(vec2 mean, vec3 conic, float bound, uint row, uint x_lo, uint x_hi) {
    const float a = conic.x, b = conic.y, c = conic.z;
    precise const float det = a * c - b * b;
    if (!(a > 0.0 && c > 0.0 && det > 0.0)) return uvec2(x_lo, x_hi);
    precise const float y_reach = sqrt(bound * a / det);   // half-height of the ellipse
    precise const float x_reach = sqrt(bound * c / det);   // half-width
    precise const float band_lo = max(float(row * TILE_HEIGHT) - mean.y, -y_reach);
    precise const float band_hi = min(float(row * TILE_HEIGHT + TILE_HEIGHT - 1u) - mean.y, y_reach);
    if (band_lo > band_hi) return uvec2(x_lo, x_lo);
    precise const float dy_right = clamp(-b * x_reach / c, band_lo, band_hi);
    precise const float dy_left = clamp(b * x_reach / c, band_lo, band_hi);
    precise const float right = (-b * dy_right + sqrt(max(bound * a - det * dy_right * dy_right, 0.0))) / a;
    precise const float left = (-b * dy_left - sqrt(max(bound * a - det * dy_left * dy_left, 0.0))) / a;
    // Tile x meets [mean.x + left, mean.x + right] when 16 x <= right end and 16 x + 15 >= left end.
    const float first = ceil((mean.x + left - float(TILE_WIDTH - 1u)) / float(TILE_WIDTH));
    const float last = floor((mean.x + right) / float(TILE_WIDTH));
    const uint span_first = uint(clamp(first, float(x_lo), float(x_hi)));
    const uint span_end = uint(clamp(last + 1.0, float(span_first), float(x_hi)));
    return uvec2(span_first, span_end);
}

// A tile id past every real tile: emit_tile_entries pads with it if it ever finds fewer tiles than
// preprocess counted (it never should), so a splat can neither spill into its neighbour's
// entries nor leave stale ones; it sorts last and tile_ranges ignores it.
uint padding_tile(uint tile_count) { return tile_count; }

#endif
