#pragma once
// SH precision: the higher SH coefficients rounded to fewer bits of the byte SPZ stores them in
// (round(128 c + 128), clamped to 0..255), as Niantic's SPZ encoder does with its sh1Bits and
// shRestBits (5 and 4 by default): keeping b bits rounds the byte to the nearest multiple of
// 2^(8 - b). The file keeps its layout and any reader reads it; what shrinks is the entropy the
// compressor sees. Applied to the cloud itself, so that what a size or quality budget measures
// (render, file bytes) is what the file holds; an 8-bit SPZ writer then stores these values
// exactly. Other formats hold the rounded values too but quantise them on their own grids.
//
// Measured (bonsai, 399,803 Gaussians at degree 3, its 37 test views against the photos; its SPZ
// at full 8 bits: 17.9 MB, 30.717 dB): degree-1 / higher bits 8/6: 14.8 MB, -0.074 dB; 6/6:
// 13.2 MB, -0.093; 7/5: 12.5 MB, -0.327; 6/5: 11.8 MB, -0.339; the encoder's 5/4: 9.8 MB, -1.242.
#include "vksplat/scene/scene.hpp"

namespace vksplat::prune {

struct ShPrecision {
    int degree1_bits = 8;  // of the 3 degree-1 coefficients per channel
    int higher_bits = 8;   // of degrees 2 and 3
    bool operator==(const ShPrecision&) const = default;
};

// Throws InputError (naming it as "--sh-bits B1,B2", the commands' option) unless both are whole
// numbers of bits from 1 to 8.
void check_sh_precision(const ShPrecision& precision);

// `cloud` with its higher SH coefficients rounded to `precision` (check_sh_precision's range; 8
// and 8 give what an SPZ file holds anyway: SPZ's byte, clamped to [-1, 127/128]). The DC term is
// left as it is.
GaussianCloud with_sh_precision(const GaussianCloud& cloud, const ShPrecision& precision);

}  // namespace vksplat::prune
