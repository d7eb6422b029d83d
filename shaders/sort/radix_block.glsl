// The block work both radix scatter kernels share (radix_scatter.comp, radix_scatter_one_sweep.comp):
// ranking a block's keys stably by digit, and writing the block out through shared memory.
//
// Ranking: a subgroup owns a contiguous part of the block (gl_SubgroupSize * ITEMS keys) and walks
// it in rows of gl_SubgroupSize keys, one per lane, keeping a per-digit count in shared memory; a
// key's rank inside its row comes from ballots (one per digit bit) giving the lanes with the same
// digit. The block is then reordered in shared memory by digit, so that neighbouring invocations
// write neighbouring addresses (one run per digit) instead of scattering single words.
// Works for any subgroup size (subgroups must be full: workgroup size a multiple of it).
//
// The including shader defines ITEMS and MAX_SUBGROUPS (specialisation constants), includes
// shaders/sort/radix_sort.h (RADIX_MAX), enables the subgroup basic and ballot extensions, and has push
// constants `pc` with keys_in, values_in, keys_out, values_out (Uints) and shift.
#ifndef VKSPLAT_RADIX_BLOCK_GLSL
#define VKSPLAT_RADIX_BLOCK_GLSL

const uint MAX_DIGIT_BITS = 8;

// [subgroup][digit]: first the subgroup's count of each digit in its part of the block, then the
// block-local position of its first key of that digit.
shared uint counts[MAX_SUBGROUPS * RADIX_MAX];
// Per digit: output position minus block-local position (the including shader fills it).
shared uint displacement[RADIX_MAX];
// The block's keys, then its values, in block-local (digit-sorted) order.
shared uint staged[gl_WorkGroupSize.x * ITEMS];

// Loads block `block` and ranks each key among its subgroup's keys of its digit (ranks: ~0u for
// slots past count). Ends with a barrier: counts[] then holds every subgroup's digit counts.
void radix_rank_block(uint block, uint count, uint mask, out uint keys[ITEMS], out uint values[ITEMS],
                      out uint ranks[ITEMS]) {
    const uint lane = gl_SubgroupInvocationID;
    const uint column = gl_SubgroupID * RADIX_MAX;
    for (uint d = lane; d < RADIX_MAX; d += gl_SubgroupSize) counts[column + d] = 0;
    subgroupBarrier();
    const uint first = block * gl_WorkGroupSize.x * ITEMS + gl_SubgroupID * gl_SubgroupSize * ITEMS + lane;
    // Every load is issued before the first is used: in the ranking loop, behind its barriers,
    // they would wait for memory one row at a time.
    for (uint row = 0; row < ITEMS; ++row) {
        const uint index = first + row * gl_SubgroupSize;
        keys[row] = index < count ? pc.keys_in.v[index] : 0u;
        values[row] = index < count ? pc.values_in.v[index] : 0u;
    }
    for (uint row = 0; row < ITEMS; ++row) {
        const bool valid = first + row * gl_SubgroupSize < count;
        const uint digit = (keys[row] >> pc.shift) & mask;

        // A fixed trip count (bits above the digit are 0 in every valid lane, so those rounds keep
        // `same` as it is) lets compilers unroll this.
        uvec4 same = subgroupBallot(valid);
        for (uint b = 0; b < MAX_DIGIT_BITS; ++b) {
            const bool set = ((digit >> b) & 1u) != 0;
            const uvec4 ones = subgroupBallot(set);
            same &= set ? ones : ~ones;
        }
        const uint before = subgroupBallotExclusiveBitCount(same);
        const uint seen = counts[column + digit];
        ranks[row] = valid ? seen + before : 0xffffffffu;
        subgroupBarrier();  // every lane has read counts[] before it changes
        if (valid && before == 0) counts[column + digit] = seen + subgroupBallotBitCount(same);
        subgroupBarrier();
    }
    barrier();
}

// Turns digit d's per-subgroup counts into each subgroup's first position among the block's keys
// of the digit; returns the block's count of the digit.
uint radix_scan_digit(uint d) {
    uint running = 0;
    for (uint s = 0; s < gl_NumSubgroups; ++s) {
        const uint n = counts[s * RADIX_MAX + d];
        counts[s * RADIX_MAX + d] = running;
        running += n;
    }
    return running;
}

// Offsets digit d's positions by the block-local position of its first key.
void radix_offset_digit(uint d, uint local_first) {
    for (uint s = 0; s < gl_NumSubgroups; ++s) counts[s * RADIX_MAX + d] += local_first;
}

// Writes the block's block_keys keys and values, reordered through shared memory, to
// displacement[digit] + block-local position. Starts and ends with a barrier.
void radix_write_block(uint block_keys, uint mask, uint keys[ITEMS], uint values[ITEMS], uint ranks[ITEMS]) {
    const uint size = gl_WorkGroupSize.x;
    const uint column = gl_SubgroupID * RADIX_MAX;
    barrier();
    for (uint row = 0; row < ITEMS; ++row) {
        if (ranks[row] != 0xffffffffu) {
            ranks[row] += counts[column + ((keys[row] >> pc.shift) & mask)];
            staged[ranks[row]] = keys[row];
        }
    }
    barrier();
    uint destination[ITEMS];
    for (uint i = 0; i < ITEMS; ++i) {
        const uint j = i * size + gl_LocalInvocationIndex;
        if (j < block_keys) {
            const uint key = staged[j];
            destination[i] = displacement[(key >> pc.shift) & mask] + j;
            pc.keys_out.v[destination[i]] = key;
        }
    }
    barrier();
    // The same for the values.
    for (uint row = 0; row < ITEMS; ++row)
        if (ranks[row] != 0xffffffffu) staged[ranks[row]] = values[row];
    barrier();
    for (uint i = 0; i < ITEMS; ++i) {
        const uint j = i * size + gl_LocalInvocationIndex;
        if (j < block_keys) pc.values_out.v[destination[i]] = staged[j];
    }
    barrier();
}

#endif
