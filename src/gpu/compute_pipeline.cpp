#include "gpu/compute_pipeline.hpp"

#include "gpu/context_impl.hpp"
#include "gpu/vk_check.hpp"

namespace vksplat::gpu {

ComputePipeline::ComputePipeline(const Context& context, std::span<const uint32_t> spirv,
                                 uint32_t push_constant_bytes, std::vector<uint32_t> specialization,
                                 std::string name)
    : context_(context), push_constant_bytes_(push_constant_bytes), name_(std::move(name)) {
    const auto& d = context.impl();
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size_bytes();
    module_info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    VKSPLAT_VK(d.vk.vkCreateShaderModule(d.device, &module_info, nullptr, &module));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &range;
    VkResult result = d.vk.vkCreatePipelineLayout(d.device, &layout_info, nullptr, &layout_);

    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < specialization.size(); ++i)
        entries.push_back({i, static_cast<uint32_t>(i * sizeof(uint32_t)), sizeof(uint32_t)});
    VkSpecializationInfo spec{};
    spec.mapEntryCount = static_cast<uint32_t>(entries.size());
    spec.pMapEntries = entries.data();
    spec.dataSize = specialization.size() * sizeof(uint32_t);
    spec.pData = specialization.data();

    if (result == VK_SUCCESS) {
        VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        info.stage.module = module;
        info.stage.pName = "main";
        info.stage.pSpecializationInfo = specialization.empty() ? nullptr : &spec;
        info.layout = layout_;
        result = d.vk.vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
    }
    d.vk.vkDestroyShaderModule(d.device, module, nullptr);
    if (result != VK_SUCCESS) {
        if (layout_) d.vk.vkDestroyPipelineLayout(d.device, layout_, nullptr);
        throw_vk_error(result, ("creating compute pipeline '" + name_ + "'").c_str());
    }
}

ComputePipeline::~ComputePipeline() {
    const auto& d = context_.impl();
    d.vk.vkDestroyPipeline(d.device, pipeline_, nullptr);
    d.vk.vkDestroyPipelineLayout(d.device, layout_, nullptr);
}

}  // namespace vksplat::gpu
