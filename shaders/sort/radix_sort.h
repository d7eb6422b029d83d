// The radix sort's kernels (radix_*.comp), recorded by src/gpu/radix_sort.cpp (RadixSort): their
// push constants, the control and look-back words they share, and what a kernel that writes a
// sort's keys needs to count their digits instead of the histogram kernel (DigitCounting, used by
// shaders/render/preprocess.comp through radix_digit_counts.glsl).
#ifndef VKSPLAT_SORT_RADIX_SORT_H
#define VKSPLAT_SORT_RADIX_SORT_H

#include "shaders/common/buffers.h"
#include "shaders/sort/lookback_words.h"

SHADER_NAMESPACE_BEGIN(sort)

SHADER_CONST(uint, RADIX_MAX, 256)  // digits of up to 8 bits
SHADER_CONST(uint, MAX_PASSES, 4)   // keys of up to 32 bits
// Control words: [0..2] DispatchArgs, [3] count, [4] blocks (written by radix_setup or the host),
// then from RADIX_TOTALS the per-pass digit totals, totals[pass][digit].
SHADER_CONST(uint, RADIX_TOTALS, 16)
// The words through which the scatter blocks of a one-sweep sort hand each other their running
// digit counts (decoupled look-back, as in Merrill & Garland's single-pass scan and Onesweep). One
// word per (block, pass, digit): the top two bits say what the low 30 bits hold, so a flag and
// its value are read and written together by one atomic.
SHADER_CONST(uint, LOOKBACK_EMPTY, 0u)                  // the block has not counted its keys yet
SHADER_CONST(uint, LOOKBACK_AGGREGATE, 1u << 30)        // value: the block's own keys of the digit
SHADER_CONST(uint, LOOKBACK_PREFIX, 2u << 30)           // value: keys of the digit in this and every earlier block
SHADER_CONST(uint, LOOKBACK_VALUE_MASK, (1u << 30) - 1u)

// Where a kernel that writes a sort's keys counts their digits for a one-sweep sort
// (radix_digit_counts.glsl, RadixSort::record_host_setup): passes 0 when it does not.
struct DigitCounting {
    Uints totals;              // [pass][digit], zeroed by record_host_setup
    Uints lookback;            // lookback_words words to set to LOOKBACK_EMPTY
    uint digits[MAX_PASSES];   // per pass: first bit | bit count << 8
    uint passes;
    uint lookback_words;
};

// radix_setup.comp: the sort's count into control words, totals cleared.
struct RadixSetupPush {
    Uints count;
    Uints control;  // [0..2] DispatchArgs, [3] count, [4] blocks, [16..] totals[pass][digit]
    uint capacity;
    uint block;     // keys per block
};

// radix_histogram.comp (one sweep, once per sort): every pass's digit totals.
struct RadixHistogramPush {
    Uints keys;
    Uints lookback;  // [block][pass][digit]
    Uints control;   // [3] count, [4] blocks
    Uints totals;    // [pass][digit]
    uint digits[MAX_PASSES];  // per pass: first bit | bit count << 8
    uint passes;
};

// radix_block_histogram.comp (a pass of a large sort, step 1).
struct RadixBlockHistogramPush {
    Uints keys;
    Uints hist;
    Uints control;
    Uints totals;  // keys per digit in this pass (cleared by radix_setup)
    uint shift;    // first bit of the digit
    uint bits;     // digit width, 0..8 (0: every key has digit 0)
};

// radix_scan_histogram.comp (a pass of a large sort, step 2).
struct RadixScanHistogramPush {
    Uints hist;     // hist[digit * blocks + block], scanned in place
    Uints control;  // [4] blocks
    Uints totals;   // keys per digit in this pass
    uint bits;
};

// radix_scatter.comp (a pass of a large sort, step 3).
struct RadixScatterPush {
    Uints keys_in;
    Uints values_in;
    Uints keys_out;
    Uints values_out;
    Uints hist;     // exclusive-scanned histogram
    Uints control;
    uint shift;
    uint bits;
};

// radix_scatter_one_sweep.comp (a pass of a one-sweep sort, its only kernel).
struct RadixScatterOneSweepPush {
    Uints keys_in;
    Uints values_in;
    Uints keys_out;
    Uints values_out;
    LookbackWords lookback;  // [block][pass][digit], cleared by the histogram kernel
    Uints control;           // [3] count, [4] blocks
    Uints totals;            // this pass's keys per digit
    uint pass;
    uint shift;
    uint bits;
};

SHADER_NAMESPACE_END

#ifndef __cplusplus
uint lookback_index(uint block, uint pass, uint digit) { return (block * MAX_PASSES + pass) * RADIX_MAX + digit; }
#endif

#endif
