#include "vksplat/gpu/context.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "gpu/context_impl.hpp"
#include "gpu/vk_check.hpp"

namespace vksplat::gpu {
namespace {

// Vulkan 1.2 is the floor: buffer device addresses and subgroup operations are core there, and
// every driver we target (NVIDIA, AMD, Intel, Mesa incl. lavapipe, MoltenVK) offers it.
constexpr uint32_t kApiVersion = VK_API_VERSION_1_2;

void ensure_loader() {
    // volkInitialize only loads the loader's entry points; repeated calls are cheap and idempotent.
    if (volkInitialize() != VK_SUCCESS)
        throw GpuError("no Vulkan loader found (libvulkan.so.1): install libvulkan1 and a driver, "
                       "e.g. mesa-vulkan-drivers for the CPU driver lavapipe");
}

bool has_extension(const std::vector<VkExtensionProperties>& list, const char* name) {
    return std::any_of(list.begin(), list.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::vector<VkExtensionProperties> instance_extensions() {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> list(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, list.data());
    return list;
}

std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> list(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, list.data());
    return list;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        auto* impl = static_cast<Context::Impl*>(user);
        std::lock_guard lock(impl->messages_mutex);
        impl->validation_messages.emplace_back(data->pMessage ? data->pMessage : "");
    }
    return VK_FALSE;
}

// volk's instance-level entry points are global and follow the instance loaded last, so once another
// Context or list_devices() has made an instance (without debug utils), the global
// vkDestroyDebugUtilsMessengerEXT is null or belongs to that one: look it up on our own instance.
void destroy_messenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
    const auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
}

struct InstanceHandle {
    VkInstance instance = VK_NULL_HANDLE;
    ~InstanceHandle() {
        if (instance) vkDestroyInstance(instance, nullptr);
    }
};

VkInstance create_instance(bool validation, Context::Impl* impl_for_messages) {
    ensure_loader();
    const auto available = instance_extensions();
    std::vector<const char*> extensions;
    VkInstanceCreateFlags flags = 0;
    // MoltenVK devices are only listed when the application opts into portability enumeration.
    if (has_extension(available, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
        extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
        flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
    }
    std::vector<const char*> layers;
    const bool debug_utils = validation && has_extension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation) {
        if (!has_layer("VK_LAYER_KHRONOS_validation"))
            throw GpuError("validation was requested but VK_LAYER_KHRONOS_validation is not installed "
                           "(Debian: vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
        if (debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "vksplat";
    app.pEngineName = "vksplat";
    app.apiVersion = kApiVersion;

    // Synchronisation validation catches missing barriers between our passes.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = on_validation_message;
    messenger_info.pUserData = impl_for_messages;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.flags = flags;
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    if (validation) {
        info.pNext = &features;
        if (debug_utils && impl_for_messages) features.pNext = &messenger_info;
    }
    VkInstance instance = VK_NULL_HANDLE;
    VKSPLAT_VK(vkCreateInstance(&info, nullptr, &instance));
    volkLoadInstanceOnly(instance);
    if (validation && debug_utils && impl_for_messages)
        VKSPLAT_VK(vkCreateDebugUtilsMessengerEXT(instance, &messenger_info, nullptr, &impl_for_messages->messenger));
    return instance;
}

int find_compute_queue_family(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    // Prefer a queue that has timestamps; any compute queue works without them.
    int fallback = -1;
    for (uint32_t i = 0; i < count; ++i) {
        if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
        if (families[i].timestampValidBits > 0) return static_cast<int>(i);
        if (fallback < 0) fallback = static_cast<int>(i);
    }
    return fallback;
}

DeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
    DeviceInfo info;
    info.index = index;

    VkPhysicalDeviceSubgroupSizeControlPropertiesEXT size_control{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES_EXT};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    const auto extensions = device_extensions(device);
    VkPhysicalDeviceProperties basic{};
    vkGetPhysicalDeviceProperties(device, &basic);
    const bool has_size_control = basic.apiVersion >= VK_API_VERSION_1_3 ||
                                  has_extension(extensions, VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME);
    subgroup.pNext = &driver;
    if (has_size_control) driver.pNext = &size_control;
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device, &properties);

    info.name = basic.deviceName;
    info.type = basic.deviceType;
    info.api_version = basic.apiVersion;
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info.subgroup_size = subgroup.subgroupSize;
    info.min_subgroup_size = has_size_control && size_control.minSubgroupSize > 0
                                 ? std::min(size_control.minSubgroupSize, subgroup.subgroupSize)
                                 : subgroup.subgroupSize;
    info.max_workgroup_invocations = basic.limits.maxComputeWorkGroupInvocations;
    info.max_shared_memory_bytes = basic.limits.maxComputeSharedMemorySize;

    // A physical-device query may chain a device extension's structure once the device offers
    // it; the extension need not be enabled on a VkDevice.
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    const bool has_budget = has_extension(extensions, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    VkPhysicalDeviceMemoryProperties2 memory2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    if (has_budget) memory2.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(device, &memory2);
    const VkPhysicalDeviceMemoryProperties& memory = memory2.memoryProperties;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if ((memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
            memory.memoryHeaps[i].size > info.device_local_bytes) {
            info.device_local_bytes = memory.memoryHeaps[i].size;
            info.device_local_budget = has_budget && budget.heapBudget[i] > 0
                                           ? std::min<uint64_t>(budget.heapBudget[i], memory.memoryHeaps[i].size)
                                           : memory.memoryHeaps[i].size;
        }

    const int family = find_compute_queue_family(device);
    if (family >= 0) {
        uint32_t count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
        if (families[family].timestampValidBits > 0) info.timestamp_period_ns = basic.limits.timestampPeriod;
    }

    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT float_atomics{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features12;
    const bool has_float_atomics = has_extension(extensions, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    if (has_float_atomics) features12.pNext = &float_atomics;
    if (basic.apiVersion >= VK_API_VERSION_1_2) vkGetPhysicalDeviceFeatures2(device, &features);

    info.int64_atomics = features.features.shaderInt64 && features12.shaderBufferInt64Atomics;
    info.float_atomics = has_float_atomics && float_atomics.shaderBufferFloat32AtomicAdd;
    info.pipeline_statistics = has_extension(extensions, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);

    const VkSubgroupFeatureFlags needed_ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT |
                                              VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT;
    if (basic.apiVersion < VK_API_VERSION_1_2)
        info.unusable_reason = "Vulkan 1.2 is required";
    else if (family < 0)
        info.unusable_reason = "no compute queue";
    else if (!features12.bufferDeviceAddress)
        info.unusable_reason = "bufferDeviceAddress is not supported";
    else if ((subgroup.supportedOperations & needed_ops) != needed_ops ||
             !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
        info.unusable_reason = "subgroup ballot, arithmetic and shuffle operations in compute shaders are required";
    else if (info.subgroup_size < 4 || info.subgroup_size > 128)
        info.unusable_reason = "subgroup size " + std::to_string(info.subgroup_size) + " is outside 4..128";
    info.usable = info.unusable_reason.empty();
    return info;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
    uint32_t count = 0;
    VKSPLAT_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VKSPLAT_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

int type_rank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

std::string list_for_message(const std::vector<DeviceInfo>& infos) {
    std::string text;
    for (const auto& info : infos)
        text += "\n  [" + std::to_string(info.index) + "] " + info.name +
                (info.usable ? "" : " (unusable: " + info.unusable_reason + ")");
    return text.empty() ? " (none)" : text;
}

uint32_t choose_device(const std::vector<DeviceInfo>& infos, const std::string& wanted) {
    if (infos.empty()) throw GpuError("no Vulkan device found: install a driver (e.g. mesa-vulkan-drivers)");
    if (!wanted.empty()) {
        const bool numeric = std::all_of(wanted.begin(), wanted.end(), [](char c) { return c >= '0' && c <= '9'; });
        for (const auto& info : infos) {
            const bool match = numeric ? std::to_string(info.index) == wanted : info.name.find(wanted) != std::string::npos;
            if (!match) continue;
            if (!info.usable) throw GpuError("device '" + info.name + "' cannot run vksplat: " + info.unusable_reason);
            return info.index;
        }
        throw GpuError("no Vulkan device matches '" + wanted + "'; devices:" + list_for_message(infos));
    }
    const DeviceInfo* best = nullptr;
    for (const auto& info : infos)
        if (info.usable && (!best || type_rank(info.type) < type_rank(best->type))) best = &info;
    if (!best) throw GpuError("no usable Vulkan device; devices:" + list_for_message(infos));
    return best->index;
}

}  // namespace

std::string DeviceInfo::type_name() const {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
        default: return "other";
    }
}

bool validation_layer_installed() {
    ensure_loader();
    return has_layer("VK_LAYER_KHRONOS_validation");
}

std::vector<DeviceInfo> list_devices() {
    InstanceHandle handle{create_instance(false, nullptr)};
    std::vector<DeviceInfo> infos;
    const auto devices = physical_devices(handle.instance);
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
    return infos;
}

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->memory_budget = options.memory_budget;
    Impl& d = *impl_;
    d.instance = create_instance(options.validation, &d);
    try {
        const auto devices = physical_devices(d.instance);
        std::vector<DeviceInfo> infos;
        for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
        const uint32_t chosen = choose_device(infos, options.device);
        d.physical_device = devices[chosen];
        d.info = infos[chosen];
        d.queue_family = static_cast<uint32_t>(find_compute_queue_family(d.physical_device));
        vkGetPhysicalDeviceMemoryProperties(d.physical_device, &d.memory);

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = d.queue_family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;

        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.bufferDeviceAddress = VK_TRUE;
        features12.shaderBufferInt64Atomics = d.info.int64_atomics;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.features.shaderInt64 = d.info.int64_atomics;
        features.pNext = &features12;
        VkPhysicalDeviceShaderAtomicFloatFeaturesEXT float_atomics{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
        float_atomics.shaderBufferFloat32AtomicAdd = VK_TRUE;

        std::vector<const char*> extensions;
        // A portability (MoltenVK) device must be created with this extension enabled.
        if (has_extension(device_extensions(d.physical_device), "VK_KHR_portability_subset"))
            extensions.push_back("VK_KHR_portability_subset");
        if (d.info.float_atomics) {
            extensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
            features12.pNext = &float_atomics;
        }
        VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_info{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
        if (options.pipeline_statistics && d.info.pipeline_statistics) {
            extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
            executable_info.pipelineExecutableInfo = VK_TRUE;
            executable_info.pNext = features.pNext;
            features.pNext = &executable_info;
            d.capture_statistics = true;
        }

        VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        info.pNext = &features;
        info.queueCreateInfoCount = 1;
        info.pQueueCreateInfos = &queue_info;
        info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
        info.ppEnabledExtensionNames = extensions.data();
        VKSPLAT_VK(vkCreateDevice(d.physical_device, &info, nullptr, &d.device));
        volkLoadDeviceTable(&d.vk, d.device);
        d.vk.vkGetDeviceQueue(d.device, d.queue_family, 0, &d.queue);
    } catch (...) {
        if (d.messenger) destroy_messenger(d.instance, d.messenger);
        vkDestroyInstance(d.instance, nullptr);
        throw;
    }
}

Context::Context(const AdoptedDevice& adopted) : impl_(std::make_unique<Impl>()) {
    Impl& d = *impl_;
    if (!adopted.instance || !adopted.physical_device || !adopted.device || !adopted.queue)
        throw GpuError("adopting a device needs the instance, physical device, device and queue (one is null)");
    d.owned = false;
    if (adopted.get_instance_proc_addr)
        volkInitializeCustom(adopted.get_instance_proc_addr);
    else
        ensure_loader();
    volkLoadInstanceOnly(adopted.instance);
    d.instance = adopted.instance;
    d.physical_device = adopted.physical_device;
    d.device = adopted.device;
    d.queue = adopted.queue;
    d.queue_family = adopted.queue_family;

    const auto devices = physical_devices(d.instance);
    const auto found = std::find(devices.begin(), devices.end(), d.physical_device);
    if (found == devices.end()) throw GpuError("the adopted physical device does not belong to the adopted instance");
    d.info = describe(d.physical_device, static_cast<uint32_t>(found - devices.begin()));
    if (!d.info.usable) throw GpuError("device '" + d.info.name + "' cannot run vksplat: " + d.info.unusable_reason);
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical_device, &family_count, families.data());
    if (d.queue_family >= family_count || !(families[d.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT))
        throw GpuError("adopted queue family " + std::to_string(d.queue_family) + " of '" + d.info.name +
                       "' has no compute queues");
    // Timestamps and 64-bit atomics are used only where the application's queue and device have them.
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(d.physical_device, &properties);
    d.info.timestamp_period_ns =
        families[d.queue_family].timestampValidBits > 0 ? properties.limits.timestampPeriod : 0.0f;
    d.info.int64_atomics = d.info.int64_atomics && adopted.int64_atomics_enabled;
    d.info.float_atomics = d.info.float_atomics && adopted.float_atomics_enabled;
    vkGetPhysicalDeviceMemoryProperties(d.physical_device, &d.memory);
    volkLoadDeviceTable(&d.vk, d.device);
}

Context::~Context() {
    Impl& d = *impl_;
    if (!d.owned) return;
    if (d.device) {
        d.vk.vkDeviceWaitIdle(d.device);
        d.vk.vkDestroyDevice(d.device, nullptr);
    }
    if (d.messenger) destroy_messenger(d.instance, d.messenger);
    if (d.instance) vkDestroyInstance(d.instance, nullptr);
}

VkInstance Context::instance() const { return impl_->instance; }
VkPhysicalDevice Context::physical_device() const { return impl_->physical_device; }
VkDevice Context::device() const { return impl_->device; }
VkQueue Context::queue() const { return impl_->queue; }
uint32_t Context::queue_family() const { return impl_->queue_family; }
const DeviceInfo& Context::info() const { return impl_->info; }
uint64_t Context::memory_budget() const {
    return impl_->memory_budget > 0 ? impl_->memory_budget : impl_->info.device_local_budget;
}
bool Context::owns_device() const { return impl_->owned; }

std::vector<std::string> Context::validation_messages() const {
    std::lock_guard lock(impl_->messages_mutex);
    return impl_->validation_messages;
}

std::vector<PipelineStatistics> Context::pipeline_statistics() const {
    std::lock_guard lock(impl_->statistics_mutex);
    return impl_->statistics;
}

void Context::Impl::device_bytes_allocated(uint64_t bytes) const {
    const uint64_t held = held_device_bytes.fetch_add(bytes) + bytes;
    uint64_t peak = peak_device_bytes.load();
    while (held > peak && !peak_device_bytes.compare_exchange_weak(peak, held)) {
    }
}

uint64_t Context::held_device_bytes() const { return impl_->held_device_bytes.load(); }
uint64_t Context::peak_device_bytes() const { return impl_->peak_device_bytes.load(); }
void Context::reset_peak_device_bytes() const { impl_->peak_device_bytes.store(impl_->held_device_bytes.load()); }

}  // namespace vksplat::gpu
