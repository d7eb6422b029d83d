// Random numbers from a hash of indices, so that a draw depends on nothing but its seed and
// position: a run repeats exactly, on any device, whatever order the invocations run in.
#ifndef VKSPLAT_COMMON_HASH_GLSL
#define VKSPLAT_COMMON_HASH_GLSL

// PCG's output hash (O'Neill 2014, as Jarzynski & Olano 2020 use it for GPU noise).
uint pcg_hash(uint v) {
    const uint state = v * 747796405u + 2891336453u;
    const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

#endif
