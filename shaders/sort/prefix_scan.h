// The prefix scan's kernels (scan_setup.comp, scan_lookback.comp), recorded by
// src/gpu/prefix_scan.cpp (PrefixScan): their push constants and control words.
#ifndef VKSPLAT_SORT_PREFIX_SCAN_H
#define VKSPLAT_SORT_PREFIX_SCAN_H

#include "shaders/common/buffers.h"
#include "shaders/sort/lookback_words.h"

SHADER_NAMESPACE_BEGIN(sort)

// Control words: [0..2] DispatchArgs, [3] count (clamped to capacity), [4] number of blocks,
// [SCAN_LOOKBACK..] one look-back word per block.
SHADER_CONST(uint, SCAN_LOOKBACK, 16)

// scan_setup.comp (one workgroup): the count into control words, look-back words cleared.
struct ScanSetupPush {
    Uints count;     // one uint: number of elements
    Uints control;   // scratch: [0..2] DispatchArgs, [3] count, [4] blocks, [16..] look-back words
    uint capacity;   // scratch capacity in elements
    uint block;      // elements per block
};

// scan_lookback.comp: the scan itself.
struct ScanLookbackPush {
    Uints input_values;
    OPTIONAL_ADDRESS(Uints) gather;  // uint indices, or 0: element i is input[gather[i]]
    Uints output_values;
    LookbackWords control;           // [3] count, [4] blocks, [16 + block] look-back word
    OPTIONAL_ADDRESS(Uints) total;   // one uint for the sum of all elements, or 0
};

SHADER_NAMESPACE_END

#endif
