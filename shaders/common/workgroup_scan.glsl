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

// WGS_DEFINE_EXCLUSIVE_ADD(T, NAME, PARTIALS) defines
//     T NAME(T value, out T total)
// for T = uint or a uint vector (uvec2: two counters per component, ...): the exclusive prefix
// sum of `value` over the workgroup in invocation order (gl_SubgroupID * gl_SubgroupSize +
// gl_SubgroupInvocationID); `total` receives the sum of all. Sums wrap modulo 2^32 per component,
// so counters packed into bit fields stay exact where every prefix fits its field. Every
// invocation of the workgroup must call it (uniform control flow). It ends with a barrier, so it
// may be called again right away. PARTIALS names its shared array: one partial per subgroup, plus
// the workgroup total in the last slot. The first subgroup scans the per-subgroup sums,
// gl_SubgroupSize at a time, as there may be more subgroups than lanes (128 invocations in
// subgroups of 4). A macro, so that each element type is one body (GLSL has no templates).
#define WGS_DEFINE_EXCLUSIVE_ADD(T, NAME, PARTIALS)                                                 \
    shared T PARTIALS[WGS_MAX_SUBGROUPS + 1];                                                       \
    T NAME(T value, out T total) {                                                                  \
        const T inclusive = subgroupInclusiveAdd(value);                                            \
        if (gl_SubgroupInvocationID == gl_SubgroupSize - 1) PARTIALS[gl_SubgroupID] = inclusive;    \
        barrier();                                                                                  \
        if (gl_SubgroupID == 0) {                                                                   \
            T carry = T(0u);                                                                        \
            for (uint base = 0; base < gl_NumSubgroups; base += gl_SubgroupSize) {                  \
                const uint i = base + gl_SubgroupInvocationID;                                      \
                const T v = i < gl_NumSubgroups ? PARTIALS[i] : T(0u);                              \
                const T inc = subgroupInclusiveAdd(v);                                              \
                if (i < gl_NumSubgroups) PARTIALS[i] = carry + inc - v;                             \
                carry += subgroupAdd(v);                                                            \
            }                                                                                       \
            if (subgroupElect()) PARTIALS[WGS_MAX_SUBGROUPS] = carry;                               \
        }                                                                                           \
        barrier();                                                                                  \
        const T result = PARTIALS[gl_SubgroupID] + inclusive - value;                               \
        total = PARTIALS[WGS_MAX_SUBGROUPS];                                                        \
        barrier();                                                                                  \
        return result;                                                                              \
    }

WGS_DEFINE_EXCLUSIVE_ADD(uint, workgroup_exclusive_add, wgs_partials)

// Sum of `value` over the workgroup, returned to every invocation (same rules as above).
uint workgroup_add(uint value) {
    uint total;
    workgroup_exclusive_add(value, total);
    return total;
}

#endif
