#version 460
#extension GL_GOOGLE_include_directive : require
// RadixSort, a pass of a large sort, step 3: each workgroup re-reads its blocks and moves every
// (key, value) to its stable position (radix_scatter_one_sweep.comp ranks the same way; it takes
// the first two terms below from totals and look-back instead). Output position of a key =
//   scanned hist[digit * blocks + block]   (keys of smaller digits, and of its digit in earlier blocks)
// + its rank among the block's keys of its digit (earlier subgroups' parts, then earlier rows
//   and lanes of its own part).
// A subgroup owns a contiguous part of the block (gl_SubgroupSize * ITEMS keys) and walks it in
// rows of gl_SubgroupSize keys, one per lane, keeping a per-digit count in shared memory; a key's
// rank inside its row comes from ballots (one per digit bit) giving the lanes with the same digit.
// The block is then reordered in shared memory by digit, so that neighbouring invocations write
// neighbouring addresses (one run per digit) instead of scattering single words.
// Works for any subgroup size (subgroups must be full: workgroup size a multiple of it).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "buffers.glsl"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;          // rows per subgroup = keys per invocation
layout(constant_id = 2) const uint MAX_SUBGROUPS = 16;  // workgroup size / smallest subgroup size
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "workgroup_scan.glsl"

const uint MAX_DIGIT_BITS = 8;
const uint RADIX_MAX = 1u << MAX_DIGIT_BITS;
const uint DIGITS_PER_INVOCATION = (RADIX_MAX + gl_WorkGroupSize.x - 1) / gl_WorkGroupSize.x;

layout(push_constant) uniform Push {
    Uints keys_in;
    Uints values_in;
    Uints keys_out;
    Uints values_out;
    Uints hist;     // exclusive-scanned histogram
    Uints control;
    uint shift;
    uint bits;
} pc;

// [subgroup][digit]: first the subgroup's count of each digit in its part of the block, then the
// block-local position of its first key of that digit.
shared uint counts[MAX_SUBGROUPS * RADIX_MAX];
// Per digit: output position minus block-local position.
shared uint displacement[RADIX_MAX];
// The block's keys, then its values, in block-local (digit-sorted) order.
shared uint staged[gl_WorkGroupSize.x * ITEMS];

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint block_size = size * ITEMS;
    const uint mask = (1u << pc.bits) - 1u;
    const uint lane = gl_SubgroupInvocationID;
    const uint column = gl_SubgroupID * RADIX_MAX;

    for (uint block = gl_WorkGroupID.x; block < blocks; block += gl_NumWorkGroups.x) {
        for (uint d = lane; d < RADIX_MAX; d += gl_SubgroupSize) counts[column + d] = 0;
        subgroupBarrier();

        // 1. Rank each key among this subgroup's keys of its digit, row by row.
        const uint first = block * block_size + gl_SubgroupID * gl_SubgroupSize * ITEMS + lane;
        uint keys[ITEMS];
        uint values[ITEMS];
        uint ranks[ITEMS];  // rank within the subgroup's keys of the digit, later block-local position
        for (uint row = 0; row < ITEMS; ++row) {
            const uint index = first + row * gl_SubgroupSize;
            const bool valid = index < count;
            keys[row] = valid ? pc.keys_in.v[index] : 0u;
            values[row] = valid ? pc.values_in.v[index] : 0u;
            const uint digit = (keys[row] >> pc.shift) & mask;

            // A fixed trip count (bits above the digit are 0 in every valid lane, so those
            // rounds keep `same` as it is) lets compilers unroll this.
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

        // 2. Block-local positions: each invocation takes DIGITS_PER_INVOCATION consecutive
        // digits, scans them over the subgroups, and a workgroup scan (in the order below)
        // orders the digits.
        const uint digit0 = (gl_SubgroupID * gl_SubgroupSize + lane) * DIGITS_PER_INVOCATION;
        uint digit_count[DIGITS_PER_INVOCATION];
        uint my_keys = 0;
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            uint running = 0;
            if (d < RADIX_MAX) {
                for (uint s = 0; s < gl_NumSubgroups; ++s) {
                    const uint n = counts[s * RADIX_MAX + d];
                    counts[s * RADIX_MAX + d] = running;
                    running += n;
                }
            }
            digit_count[i] = running;
            my_keys += running;
        }
        uint block_keys;
        uint local_start = workgroup_exclusive_add(my_keys, block_keys);
        for (uint i = 0; i < DIGITS_PER_INVOCATION; ++i) {
            const uint d = digit0 + i;
            if (d < RADIX_MAX) {
                for (uint s = 0; s < gl_NumSubgroups; ++s) counts[s * RADIX_MAX + d] += local_start;
                if (digit_count[i] != 0) displacement[d] = pc.hist.v[d * blocks + block] - local_start;
            }
            local_start += digit_count[i];
        }
        barrier();

        // 3. Reorder keys through shared memory and write them out in runs.
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
        // 4. The same for the values.
        for (uint row = 0; row < ITEMS; ++row)
            if (ranks[row] != 0xffffffffu) staged[ranks[row]] = values[row];
        barrier();
        for (uint i = 0; i < ITEMS; ++i) {
            const uint j = i * size + gl_LocalInvocationIndex;
            if (j < block_keys) pc.values_out.v[destination[i]] = staged[j];
        }
        barrier();
    }
}
