// The push constants of one blend variant. No include guard: shaders/render/blend.h includes it
// once per variant, with BLEND_PUSH naming the struct and TRAIN_OUTPUTS, GATHER_STATS and
// CARRY_STATE (0 or 1) choosing its members.
struct BLEND_PUSH {
    CameraBuffer camera;
    UVec2s ranges;
    Uints tile_values;
    Footprints footprints;
    Vec4s colors;            // rgb and view depth
    Vec4s out_color_alpha;   // rgb + background * T, and alpha = 1 - T
    Floats out_depth;        // expected depth of the blended splats
    Uints out_contributors;  // splats blended into the pixel
#if TRAIN_OUTPUTS
    Floats out_transmittance;  // final T
    Uints out_last;            // one past the position (in the tile's list) of the last splat blended
#endif
#if GATHER_STATS
    Uint64s stat_weight;     // per Gaussian: sum of alpha * T (fixed point)
    Uints stat_max_weight;   // per Gaussian: max alpha * T as float bits (non-negative, so uint order)
    Uints stat_pixels;       // per Gaussian: pixels where alpha >= 1/255
    Uints stat_centre_weight;  // per Gaussian: alpha * T at the pixel holding its centre (float bits)
#endif
#if CARRY_STATE
    // Two buffers and a word, so that even the statistics variant stays within the 128 bytes of
    // push constants every device has.
    Vec4s carried_color;          // colour so far (rgb, no background) and transmittance (a)
    Vec2s carried_depth_count;    // sum of depth * weight so far; splats blended so far as uint
                                  // bits, with CARRY_STOPPED once the pixel stopped
    uint carry_flags;             // CARRY_LOAD | CARRY_LAST
#endif
};
