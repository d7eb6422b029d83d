#include "gpu/compute_pipeline.hpp"

#include "gpu/context_impl.hpp"
#include "gpu/vk_check.hpp"

#include <mutex>

namespace vksplat::gpu {
namespace {

std::string statistic_text(const VkPipelineExecutableStatisticKHR& statistic) {
    switch (statistic.format) {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: return statistic.value.b32 ? "true" : "false";
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: return std::to_string(statistic.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: return std::to_string(statistic.value.u64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: return std::to_string(statistic.value.f64);
    default: return "?";
    }
}

// The driver's statistics of every executable of `pipeline` (a compute pipeline has one; where
// a driver splits it, each statistic is named "executable: statistic").
PipelineStatistics read_statistics(const Context::Impl& d, VkPipeline pipeline, const std::string& name) {
    PipelineStatistics out{name, {}};
    VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    uint32_t executables = 0;
    if (d.vk.vkGetPipelineExecutablePropertiesKHR(d.device, &info, &executables, nullptr) != VK_SUCCESS) return out;
    std::vector<VkPipelineExecutablePropertiesKHR> properties(executables,
                                                              {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
    d.vk.vkGetPipelineExecutablePropertiesKHR(d.device, &info, &executables, properties.data());
    for (uint32_t e = 0; e < executables; ++e) {
        VkPipelineExecutableInfoKHR executable{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        executable.pipeline = pipeline;
        executable.executableIndex = e;
        uint32_t count = 0;
        if (d.vk.vkGetPipelineExecutableStatisticsKHR(d.device, &executable, &count, nullptr) != VK_SUCCESS) continue;
        std::vector<VkPipelineExecutableStatisticKHR> statistics(count,
                                                                 {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        d.vk.vkGetPipelineExecutableStatisticsKHR(d.device, &executable, &count, statistics.data());
        const std::string prefix = executables > 1 ? std::string(properties[e].name) + ": " : "";
        for (uint32_t i = 0; i < count; ++i)
            out.values.emplace_back(prefix + statistics[i].name, statistic_text(statistics[i]));
    }
    return out;
}

}  // namespace

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
        if (d.capture_statistics) info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
        result = d.vk.vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
    }
    if (result == VK_SUCCESS && d.capture_statistics) {
        PipelineStatistics statistics = read_statistics(d, pipeline_, name_);
        Context::Impl& shared = context.impl();  // pipelines of one context may be built on several threads
        std::lock_guard lock(shared.statistics_mutex);
        shared.statistics.push_back(std::move(statistics));
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
