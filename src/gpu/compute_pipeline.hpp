#pragma once
// ComputePipeline: one compute shader (embedded SPIR-V) with a push-constant block and
// specialisation constants (ids 0..n-1, 32-bit each). RAII over the pipeline and its layout.
// Passes build it as a gpu::Kernel<K> (gpu/kernel.hpp), which names the shader and its push type.
#include <volk.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vksplat/gpu/context.hpp"

namespace vksplat::gpu {

class ComputePipeline {
public:
    ComputePipeline(const Context& context, std::span<const uint32_t> spirv, uint32_t push_constant_bytes,
                    std::vector<uint32_t> specialization = {}, std::string name = "");
    virtual ~ComputePipeline();  // owned through a PushKernel<P> where a pass takes several shaders
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    uint32_t push_constant_bytes() const { return push_constant_bytes_; }
    const std::string& name() const { return name_; }

private:
    const Context& context_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    uint32_t push_constant_bytes_ = 0;
    std::string name_;
};

}  // namespace vksplat::gpu
