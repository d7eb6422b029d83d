#pragma once
// Kernel<K>: the pipeline of one generated kernel K (shaders/<module>/<name>.kernel.hpp, made by
// cmake/EmbedKernel.cmake from the shader): K names its SPIR-V, its push type and its name once,
// and CommandStream::dispatch takes a Kernel<K> only with a K::Push, so a dispatch with another
// pass's push does not compile. A pass that runs whichever of several shaders sharing one push
// type its owner gives it holds a PushKernel<P>, the base of every Kernel<K> whose push is P.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gpu/compute_pipeline.hpp"

namespace vksplat::gpu {

template <class P>
class PushKernel : public ComputePipeline {
public:
    using Push = P;
    // Every Vulkan device holds 128 bytes of push constants; larger pushes would fail on some.
    static_assert(sizeof(Push) <= 128, "a push block must fit the 128 bytes every device has");

protected:
    PushKernel(const Context& context, std::span<const uint32_t> spirv, std::vector<uint32_t> specialization,
               const char* name)
        : ComputePipeline(context, spirv, sizeof(Push), std::move(specialization), name) {}
};

template <class K>
class Kernel : public PushKernel<typename K::Push> {
public:
    // specialization: the shader's specialisation constants, ids 0..n-1.
    explicit Kernel(const Context& context, std::vector<uint32_t> specialization = {})
        : PushKernel<typename K::Push>(context, K::spirv(), std::move(specialization), K::name) {}
};

// Workgroups for a grid-stride loop over `count` elements, per_group per group, at most 65535
// groups (MAX_GROUPS_X of shaders/common/buffers.h).
inline uint32_t groups_for(uint32_t count, uint32_t per_group = 256) {
    const uint64_t groups = (static_cast<uint64_t>(count) + per_group - 1) / per_group;
    return static_cast<uint32_t>(groups < 65535 ? groups : 65535);
}

}  // namespace vksplat::gpu
