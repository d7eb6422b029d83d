// The words through which the radix sort's scatter blocks hand each other their running digit
// counts (decoupled look-back, as in Merrill & Garland's single-pass scan and Onesweep). One
// word per (block, pass, digit): the top two bits say what the low 30 bits hold, so a flag and
// its value are read and written together by one atomic.
#ifndef VKSPLAT_RADIX_LOOKBACK_GLSL
#define VKSPLAT_RADIX_LOOKBACK_GLSL

const uint RADIX_MAX = 256;  // digits of up to 8 bits
const uint MAX_PASSES = 4;   // keys of up to 32 bits
// Control word of the first per-pass digit total, totals[pass][digit] (kTotalsOffset / 4 in radix_sort.cpp).
const uint RADIX_TOTALS = 16;
const uint LOOKBACK_EMPTY = 0u;                 // the block has not counted its keys yet
const uint LOOKBACK_AGGREGATE = 1u << 30;       // value: the block's own keys of the digit
const uint LOOKBACK_PREFIX = 2u << 30;          // value: keys of the digit in this and every earlier block
const uint LOOKBACK_VALUE_MASK = (1u << 30) - 1u;

uint lookback_index(uint block, uint pass, uint digit) { return (block * MAX_PASSES + pass) * RADIX_MAX + digit; }

#endif
