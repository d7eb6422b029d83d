#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort, a pass of a one-sweep sort (the only kernel per pass): each workgroup takes a block of
// keys, ranks them stably by this pass's digit, learns how many keys of each digit earlier blocks
// hold, and moves every (key, value) to its stable position (ranking and writing: radix_block.glsl):
//   keys of smaller digits (the histogram kernel's totals)
// + keys of its digit in earlier blocks (decoupled look-back, below)
// + its rank among the block's keys of its digit.
//
// Look-back: as soon as a block has counted its digits it publishes them (AGGREGATE), and once it
// knows its earlier blocks' counts too, their sum with its own (PREFIX). A block walks back over
// its predecessors adding AGGREGATEs until it meets a PREFIX. Waiting on a predecessor that has
// not published would assume it gets to run, which Vulkan does not promise (workgroups need not
// be scheduled fairly, nor in order), so after SPIN_LIMIT rounds of polls the block counts that
// predecessor's keys itself (decoupled fallback, Smith, Levien & Owens 2025): slower, never stuck.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_memory_scope_semantics : require
#include "shaders/sort/radix_sort.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;          // rows per subgroup = keys per invocation
layout(constant_id = 2) const uint MAX_SUBGROUPS = 16;  // workgroup size / smallest subgroup size
layout(constant_id = 3) const uint SPIN_LIMIT = 64;     // polls of an unpublished predecessor before counting it
const uint WINDOW = 8;  // predecessors read per look-back round trip
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "shaders/common/workgroup_scan.glsl"

const uint DIGITS_PER_INVOCATION = (RADIX_MAX + gl_WorkGroupSize.x - 1) / gl_WorkGroupSize.x;

layout(push_constant) uniform Push { RadixScatterOneSweepPush pc; };

#include "shaders/sort/radix_block.glsl"

// A predecessor's digit counts, when the block has to count them itself.
shared uint fallback[RADIX_MAX];
shared uint lookback_counted;  // 1 + the predecessor block the workgroup counts itself, or 0

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint block_size = size * ITEMS;
    const uint radix = 1u << pc.bits;
    const uint mask = radix - 1u;
    const uint local = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    const uint digit0 = local * DIGITS_PER_INVOCATION;

    // Keys of smaller digits, for this invocation's first digit.
    uint digit_total[DIGITS_PER_INVOCATION];
    uint my_total = 0;
    for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
        digit_total[i] = digit0 + i < radix ? pc.totals.v[digit0 + i] : 0u;
        my_total += digit_total[i];
    }
    uint all_keys;
    const uint smaller_digits = workgroup_exclusive_add(my_total, all_keys);

    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        if (gl_LocalInvocationIndex == 0) lookback_counted = 0;  // read after radix_rank_block's barrier
        uint keys[ITEMS], values[ITEMS], ranks[ITEMS];
        radix_rank_block(block, count, mask, keys, values, ranks);

        // Block-local positions: each invocation takes DIGITS_PER_INVOCATION consecutive digits,
        // scans them over the subgroups, and a workgroup scan (in the order below) orders the
        // digits. The block's count of each digit is published at once.
        uint digit_count[DIGITS_PER_INVOCATION];
        uint local_first[DIGITS_PER_INVOCATION];
        uint my_keys = 0;
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            const uint running = d < RADIX_MAX ? radix_scan_digit(d) : 0u;
            if (d < radix)
                atomicExchange(pc.lookback.v[lookback_index(block, pc.pass, d)],
                               (block == 0 ? LOOKBACK_PREFIX : LOOKBACK_AGGREGATE) | running);
            digit_count[i] = running;
            my_keys += running;
        }
        uint block_keys;
        uint local_start = workgroup_exclusive_add(my_keys, block_keys);
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            if (d < RADIX_MAX) radix_offset_digit(d, local_start);
            local_first[i] = local_start;
            local_start += digit_count[i];
        }

        // Keys of each digit in earlier blocks. Each digit walks back on its own, with no
        // barrier, reading WINDOW predecessors per round trip to memory and adding AGGREGATEs up to
        // the first PREFIX. An unpublished predecessor stops a digit there; a digit stopped for
        // SPIN_LIMIT rounds waits for the workgroup, which then counts that block's keys itself.
        uint earlier[DIGITS_PER_INVOCATION];
        uint next[DIGITS_PER_INVOCATION];  // the digit's next predecessor to read is next - 1
        bool open[DIGITS_PER_INVOCATION];
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            earlier[i] = 0;
            next[i] = block;
            open[i] = block > 0 && digit0 + i < radix;
        }
        while (true) {
            uint stalled[DIGITS_PER_INVOCATION];
            for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) stalled[i] = 0;
            bool walking = true;
            while (walking) {
                walking = false;
                for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
                    if (!open[i] || stalled[i] > SPIN_LIMIT) continue;
                    uint words[WINDOW];
                    for (uint w = 0; w < WINDOW; ++w)
                        words[w] = w < next[i] ? atomicLoad(pc.lookback.v[lookback_index(next[i] - 1 - w, pc.pass, digit0 + i)],
                                                            gl_ScopeDevice, gl_StorageSemanticsBuffer, gl_SemanticsRelaxed)
                                               : LOOKBACK_PREFIX;  // before block 0: nothing
                    const uint before = next[i];
                    for (uint w = 0; w < WINDOW && open[i]; ++w) {
                        if (words[w] == LOOKBACK_EMPTY) break;
                        earlier[i] += words[w] & LOOKBACK_VALUE_MASK;
                        --next[i];
                        open[i] = (words[w] & LOOKBACK_PREFIX) == 0 && next[i] > 0;
                    }
                    stalled[i] = next[i] == before ? stalled[i] + 1 : 0;
                    walking = walking || (open[i] && stalled[i] <= SPIN_LIMIT);
                }
            }
            for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i)
                if (open[i]) atomicMax(lookback_counted, next[i]);
            barrier();
            const uint counted = lookback_counted;  // 0: every digit is done; else 1 + the block to count
            barrier();  // read by all before it is reset
            if (counted == 0) break;
            if (gl_LocalInvocationIndex == 0) lookback_counted = 0;
            for (uint d = gl_LocalInvocationIndex; d < RADIX_MAX; d += size) fallback[d] = 0;
            barrier();
            for (uint i = 0; i < ITEMS; ++i) {
                const uint index = (counted - 1) * block_size + i * size + gl_LocalInvocationIndex;
                if (index < count) atomicAdd(fallback[(pc.keys_in.v[index] >> pc.shift) & mask], 1u);
            }
            barrier();
            for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
                if (!open[i] || next[i] != counted) continue;
                earlier[i] += fallback[digit0 + i];
                --next[i];
                open[i] = next[i] > 0;
            }
            barrier();  // fallback[] is read before it changes
        }
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            if (d >= radix) continue;
            if (block > 0)
                atomicExchange(pc.lookback.v[lookback_index(block, pc.pass, d)],
                               LOOKBACK_PREFIX | (earlier[i] + digit_count[i]));
            // smaller_digits counts the keys of this invocation's digits before d.
            uint smaller = smaller_digits;
            for (uint k = 0; k < i; ++k) smaller += digit_total[k];
            if (digit_count[i] != 0) displacement[d] = smaller + earlier[i] - local_first[i];
        }
        radix_write_block(block_keys, mask, keys, values, ranks);
    }
}
