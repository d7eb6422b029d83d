// bandwidth_copy.comp, recorded by src/bench/device_floor.cpp (the device floor's copy rate and
// the cost of a dependent dispatch): 256 invocations per workgroup.
#ifndef VKSPLAT_BENCH_BANDWIDTH_COPY_H
#define VKSPLAT_BENCH_BANDWIDTH_COPY_H

#include "shaders/common/buffers.h"

SHADER_NAMESPACE_BEGIN(bench)

struct BandwidthCopyPush {
    UVec4s source;
    UVec4s target;
    uint count;  // 16-byte words
};

SHADER_NAMESPACE_END

#endif
