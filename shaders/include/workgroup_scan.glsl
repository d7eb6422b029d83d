// Workgroup-wide exclusive prefix sum built from subgroup scans, for any subgroup size.
//
// The including shader defines WGS_MAX_SUBGROUPS (an upper bound on gl_NumSubgroups, normally a
// specialisation constant = workgroup size / smallest subgroup size) before including this file,
// and enables GL_KHR_shader_subgroup_basic and GL_KHR_shader_subgroup_arithmetic.
//
// Assumes full subgroups (workgroup size a multiple of the subgroup size), as every driver we
// know of runs them for such workgroups.
#ifndef VKSPLAT_WORKGROUP_SCAN_GLSL
#define VKSPLAT_WORKGROUP_SCAN_GLSL

#ifndef WGS_MAX_SUBGROUPS
#error "define WGS_MAX_SUBGROUPS before including workgroup_scan.glsl"
#endif

// One partial per subgroup, plus the workgroup total in the last slot.
shared uint wgs_partials[WGS_MAX_SUBGROUPS + 1];

// Exclusive prefix sum of `value` over the workgroup in invocation order
// (gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID); `total` receives the sum of all.
// Every invocation of the workgroup must call it (uniform control flow). It ends with a barrier,
// so it may be called again right away.
uint workgroup_exclusive_add(uint value, out uint total) {
    const uint inclusive = subgroupInclusiveAdd(value);
    if (gl_SubgroupInvocationID == gl_SubgroupSize - 1) wgs_partials[gl_SubgroupID] = inclusive;
    barrier();
    if (gl_SubgroupID == 0) {
        // The first subgroup scans the per-subgroup sums, gl_SubgroupSize at a time: there may be
        // more subgroups than lanes (e.g. 128 invocations in subgroups of 4).
        uint carry = 0;
        for (uint base = 0; base < gl_NumSubgroups; base += gl_SubgroupSize) {
            const uint i = base + gl_SubgroupInvocationID;
            const uint v = i < gl_NumSubgroups ? wgs_partials[i] : 0u;
            const uint inc = subgroupInclusiveAdd(v);
            if (i < gl_NumSubgroups) wgs_partials[i] = carry + inc - v;
            carry += subgroupAdd(v);
        }
        if (subgroupElect()) wgs_partials[WGS_MAX_SUBGROUPS] = carry;
    }
    barrier();
    const uint result = wgs_partials[gl_SubgroupID] + inclusive - value;
    total = wgs_partials[WGS_MAX_SUBGROUPS];
    barrier();
    return result;
}

// Sum of `value` over the workgroup, returned to every invocation (same rules as above).
uint workgroup_add(uint value) {
    uint total;
    workgroup_exclusive_add(value, total);
    return total;
}

#endif
