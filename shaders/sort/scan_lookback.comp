#version 460
#extension GL_GOOGLE_include_directive : require
// PrefixScan in one kernel (single-pass scan with decoupled look-back, Merrill & Garland 2016):
// each workgroup scans its block in shared memory (ITEMS consecutive elements per invocation + a
// workgroup scan of their sums), publishes the block's sum at once (AGGREGATE) and, once it knows
// the sum of every earlier block, that too (PREFIX); a block walks back over its predecessors,
// adding AGGREGATEs until it meets a PREFIX. A predecessor still unpublished after SPIN_LIMIT
// rounds is summed from its input by the waiting block itself (decoupled fallback, Smith, Levien &
// Owens 2025), so nothing waits on a workgroup that Vulkan never promised would run.
// A look-back word is a 2-bit flag and a 30-bit value read and written by one atomic: sums are
// exact below 2^30 and saturate there (the renderer's counts stay far below; a saturated total
// still exceeds every buffer capacity, which is what its consumers check).
// Output must not be input: a block that sums an unpublished predecessor reads its input.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_memory_scope_semantics : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "shaders/sort/prefix_scan.h"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS = 16;
layout(constant_id = 2) const uint MAX_SUBGROUPS = 32;
layout(constant_id = 3) const uint SPIN_LIMIT = 64;
#define WGS_MAX_SUBGROUPS MAX_SUBGROUPS
#include "shaders/common/workgroup_scan.glsl"

const uint AGGREGATE = 1u << 30;
const uint PREFIX = 2u << 30;
const uint VALUE_MASK = (1u << 30) - 1u;  // PrefixScan::saturated_sum

layout(push_constant) uniform Push { ScanLookbackPush pc; };

shared uint tile[gl_WorkGroupSize.x * ITEMS];
shared uint lookback_sum;   // what the first subgroup's walk added up
shared uint lookback_next;  // where it stopped (0: at the start)

uint saturated(uint a, uint b) { return min(a + min(b, VALUE_MASK), VALUE_MASK); }

// Element i of the scanned sequence (a gathered one saves the kernel that would lay it out).
uint element(uint i) {
    return (pc.gather.x | pc.gather.y) != 0 ? pc.input_values.v[Uints(pc.gather).v[i]] : pc.input_values.v[i];
}

void main() {
    const uint count = pc.control.v[3];
    const uint blocks = pc.control.v[4];
    const uint size = gl_WorkGroupSize.x;
    const uint block_size = size * ITEMS;
    // Position of this invocation in the workgroup scan's order.
    const uint local = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    for (uint block = gl_WorkGroupID.x; block < max(blocks, 1u); block += gl_NumWorkGroups.x) {
        const uint start = block * block_size;
        for (uint i = 0; i < ITEMS; ++i) {
            const uint j = i * size + gl_LocalInvocationIndex;
            tile[j] = start + j < count ? element(start + j) : 0u;
        }
        barrier();
        uint sum = 0;
        for (uint i = 0; i < ITEMS; ++i) sum += tile[local * ITEMS + i];
        uint block_total;
        const uint exclusive = workgroup_exclusive_add(sum, block_total);
        if (gl_LocalInvocationIndex == 0 && block < blocks)
            atomicExchange(pc.control.v[SCAN_LOOKBACK + block], (block == 0 ? PREFIX : AGGREGATE) | min(block_total, VALUE_MASK));

        // Sum of every earlier block: the first subgroup walks back with no barrier, reading one
        // predecessor per lane (one round trip per gl_SubgroupSize blocks) and adding AGGREGATEs
        // up to the first PREFIX. An unpublished predecessor stops the walk there; after
        // SPIN_LIMIT rounds stopped, the workgroup sums that block's input itself.
        uint earlier = 0;
        uint next = block;  // the next predecessor to read is next - 1
        while (next > 0) {
            if (gl_SubgroupID == 0) {
                const uint lane = gl_SubgroupInvocationID;
                uint stalled = 0;
                while (next > 0 && stalled <= SPIN_LIMIT) {
                    // Before block 0 there is nothing: a PREFIX of 0 ends the walk.
                    const uint word = lane < next ? atomicLoad(pc.control.v[SCAN_LOOKBACK + next - 1 - lane], gl_ScopeDevice,
                                                               gl_StorageSemanticsBuffer, gl_SemanticsRelaxed) : PREFIX;
                    const uvec4 stops = subgroupBallot(word == 0 || (word & PREFIX) != 0);
                    const uint stop = subgroupBallotBitCount(stops) != 0 ? subgroupBallotFindLSB(stops) : gl_SubgroupSize;
                    // Values below 2^30, up to 128 lanes: added in 16-bit halves so nothing wraps.
                    const uint value = lane <= stop ? word & VALUE_MASK : 0u;
                    const uint high = subgroupAdd(value >> 16), low = subgroupAdd(value & 0xffffu);
                    earlier = saturated(earlier, high >= (1u << 14) ? VALUE_MASK : saturated(high << 16, low));
                    const bool stop_is_prefix = stop < gl_SubgroupSize &&
                                                subgroupBallotBitExtract(subgroupBallot((word & PREFIX) != 0), stop);
                    stalled = stop == 0 && !stop_is_prefix ? stalled + 1 : 0;
                    next = stop_is_prefix ? 0 : next - stop;
                }
                if (subgroupElect()) {
                    lookback_sum = earlier;
                    lookback_next = next;
                }
            }
            barrier();
            earlier = lookback_sum;
            next = lookback_next;
            barrier();  // lookback_sum and lookback_next are read before they change
            if (next > 0) {
                const uint j = next - 1;
                uint part = 0;
                for (uint i = 0; i < ITEMS; ++i) {
                    const uint index = j * block_size + i * size + gl_LocalInvocationIndex;
                    if (index < count) part += element(index);
                }
                earlier = saturated(earlier, workgroup_add(part));
                next = j;
            }
        }
        if (gl_LocalInvocationIndex == 0 && block > 0 && block < blocks)
            atomicExchange(pc.control.v[SCAN_LOOKBACK + block], PREFIX | saturated(earlier, block_total));
        if (gl_LocalInvocationIndex == 0 && block + 1 >= blocks && (pc.total.x | pc.total.y) != 0)
            Uints(pc.total).v[0] = saturated(earlier, block_total);

        uint running = earlier + exclusive;
        for (uint i = 0; i < ITEMS; ++i) {
            const uint v = tile[local * ITEMS + i];
            tile[local * ITEMS + i] = running;
            running += v;
        }
        barrier();
        for (uint i = 0; i < ITEMS; ++i) {
            const uint j = i * size + gl_LocalInvocationIndex;
            if (start + j < count) pc.output_values.v[start + j] = tile[j];
        }
        barrier();
    }
}
