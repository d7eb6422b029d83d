// Per block of pixels, the splats of a blend batch that can touch it, in list order: a splat is a
// few pixels wide and meets one or two of a tile's 8 blocks (tile_blocks.glsl), and testing every
// splat's block mask in every pixel was most of a deep tile's time (lego 800² view 0: a tile of
// 4,171 splats took 0.47 ms on an H100 even alone on the GPU, ~180 cycles per splat, though its
// blocks meet 12-19% of them). Shared by the blend (blend_body.glsl) and its backward pass
// (blend_backward.glsl). The including shader defines BATCH (= its workgroup size, one splat per
// invocation) and enables the subgroup basic and arithmetic extensions.
#ifndef VKSPLAT_BLOCK_HIT_LISTS_GLSL
#define VKSPLAT_BLOCK_HIT_LISTS_GLSL

#include "shaders/render/tile_blocks.glsl"

// Any subgroup size, down to 1 (lavapipe runs 4 or 8).
#define WGS_MAX_SUBGROUPS BATCH
#include "shaders/common/workgroup_scan.glsl"
WGS_DEFINE_EXCLUSIVE_ADD(uvec2, workgroup_exclusive_add2, wgs_partials2)

// block_hits[block * BATCH + i]: the batch slot of the block's i-th splat; block_hit_count[block]
// of them.
shared uint block_hits[BLOCKS * BATCH];
shared uint block_hit_count[BLOCKS];

// The batch slot an invocation fills: list_block_hits scans the slots in this order.
uint batch_slot() { return gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID; }

// Lists the batch's splats per block: the invocation holding batch slot `slot` (batch_slot()) adds
// it to the blocks of `mask`. Positions come from one workgroup scan of all 8 blocks' counts
// packed in bytes: an exclusive count over at most 255 earlier slots fits a byte, and the
// scan's arithmetic is modulo 2^32, so carries out of a byte in its partial sums cancel. Only the
// totals can reach 256; each is taken from the last slot unpacked. Uniform control flow; ends
// with a barrier.
void list_block_hits(uint slot, uint mask) {
    const uvec2 spread = uvec2(((mask & 0x0Fu) * 0x00204081u) & 0x01010101u,
                               ((mask >> 4u) * 0x00204081u) & 0x01010101u);
    uvec2 ignored_total;
    const uvec2 before = workgroup_exclusive_add2(spread, ignored_total);
    for (uint block = 0u; block < BLOCKS; ++block) {
        const uint position = (before[block / 4u] >> (8u * (block % 4u))) & 0xFFu;
        const bool hit = (mask & (1u << block)) != 0u;
        if (hit) block_hits[block * BATCH + position] = slot;
        if (slot == BATCH - 1u) block_hit_count[block] = position + (hit ? 1u : 0u);
    }
    barrier();
}

// `mask` widened so that every block of a subgroup has the same bits: the union of the splats its
// blocks meet. A pass that sums over a subgroup per splat (the backward's gradients) needs all its
// invocations on one list; a subgroup of 32 or fewer lies within a block and changes nothing, one
// of 64 (AMD) takes two blocks' union. Extra splats are evaluated to an alpha below 1/255 and skipped.
uint subgroup_blocks(uint mask) {
    const uint span = clamp(gl_SubgroupSize / (BLOCK_SIZE.x * BLOCK_SIZE.y), 1u, BLOCKS);
    if (span == 1u) return mask;
    const uint group = (1u << span) - 1u;
    uint widened = 0u;
    for (uint first = 0u; first < BLOCKS; first += span)
        if (((mask >> first) & group) != 0u) widened |= group << first;
    return widened;
}

#endif
