// Counting the digits of a one-sweep radix sort's keys in a workgroup (shared memory), then adding
// the workgroup's counts to the sort's per-pass totals (totals[pass][digit], one atomic per
// non-zero count). The sort's histogram kernel counts this way, and so can the kernel that writes
// the keys, where the sort's setup was written by the host (RadixSort::record_host_setup): a
// key's digit in every pass is known as soon as the key is, so no kernel needs to read the keys
// again before the first scatter.
//
// Use: radix_clear_digit_counts(), barrier(), radix_count_digits() per key, then in uniform
// control flow radix_add_digit_counts() (which starts with the barrier it needs). The including
// shader enables the subgroup basic, vote and ballot extensions, includes
// shaders/sort/radix_sort.h, and includes this after its local_size layout: before it, glslang takes
// gl_WorkGroupSize to be 1 and every invocation would add the whole workgroup's counts.
#ifndef VKSPLAT_RADIX_DIGIT_COUNTS_GLSL
#define VKSPLAT_RADIX_DIGIT_COUNTS_GLSL

shared uint radix_digit_counts[MAX_PASSES * RADIX_MAX];

void radix_clear_digit_counts() {
    for (uint i = gl_LocalInvocationIndex; i < MAX_PASSES * RADIX_MAX; i += gl_WorkGroupSize.x)
        radix_digit_counts[i] = 0;
}

// digits: per pass, first bit | bit count << 8. A digit the whole subgroup shares (the high
// digits of nearby depths, the culled keys) is added once, not by every lane in turn.
void radix_count_digits(uint key, uint digits[MAX_PASSES], uint passes) {
    for (uint pass = 0; pass < passes; ++pass) {
        const uint shift = digits[pass] & 0xffu, bits = digits[pass] >> 8;
        const uint slot = pass * RADIX_MAX + ((key >> shift) & ((1u << bits) - 1u));
        if (subgroupAllEqual(slot)) {
            const uint lanes = subgroupBallotBitCount(subgroupBallot(true));
            if (subgroupElect()) atomicAdd(radix_digit_counts[slot], lanes);
        } else {
            atomicAdd(radix_digit_counts[slot], 1u);
        }
    }
}

// The producer also empties the sort's look-back words (RadixSort::DigitCounting): `words` of
// them, over all its invocations, before the scatter's barrier.
void radix_clear_lookback(Uints lookback, uint words) {
    for (uint i = gl_GlobalInvocationID.x; i < words; i += gl_NumWorkGroups.x * gl_WorkGroupSize.x)
        lookback.v[i] = LOOKBACK_EMPTY;
}

void radix_add_digit_counts(Uints totals, uint passes) {
    barrier();
    for (uint i = gl_LocalInvocationIndex; i < passes * RADIX_MAX; i += gl_WorkGroupSize.x)
        if (radix_digit_counts[i] != 0u) atomicAdd(totals.v[i], radix_digit_counts[i]);
}

#endif
