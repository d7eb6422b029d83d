#pragma once
// Context: one Vulkan device and a compute queue, owned by vksplat or adopted from the caller.
// Everything GPU-side in vksplat hangs off a Context; there is no process-wide Vulkan state of
// ours (volk's loader entry points are the one exception, and they are the same for everyone).
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vksplat::gpu {

struct DeviceInfo {
    uint32_t index = 0;                 // position in vkEnumeratePhysicalDevices
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;                 // driver name and version info
    uint32_t api_version = 0;
    uint32_t subgroup_size = 0;         // the default size compute shaders run with
    uint32_t min_subgroup_size = 0;     // smallest size the driver may pick (AMD: 32 vs 64)
    uint32_t max_workgroup_invocations = 0;  // maxComputeWorkGroupInvocations (Vulkan promises 128)
    uint32_t max_shared_memory_bytes = 0;    // maxComputeSharedMemorySize (Vulkan promises 16 KiB)
    uint64_t device_local_bytes = 0;    // largest device-local heap
    // What this process may use of that heap: VK_EXT_memory_budget's budget where the driver has
    // it (the heap less what others hold), else the heap's size.
    uint64_t device_local_budget = 0;
    float timestamp_period_ns = 0;      // 0 when the queue has no timestamps
    bool int64_atomics = false;         // 64-bit buffer atomics: needed for per-Gaussian statistics
    // 32-bit float atomic add on buffers (VK_EXT_shader_atomic_float): the backward passes add
    // gradients with it; without it they use a compare-and-swap loop (same sums, slower).
    bool float_atomics = false;
    // The driver can describe its compiled pipelines (VK_KHR_pipeline_executable_properties):
    // ContextOptions::pipeline_statistics.
    bool pipeline_statistics = false;
    bool usable = false;                // has what vksplat needs (see unusable_reason)
    std::string unusable_reason;

    std::string type_name() const;
};

struct ContextOptions {
    // "" picks the first usable discrete GPU, then integrated, then anything (lavapipe).
    // A number picks by index; any other text picks the first device whose name contains it.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation (with synchronisation validation) when installed.
    bool validation = false;
    // Device memory vksplat may hold, in bytes; 0: the device's own limit (device_local_budget).
    // A renderer whose frame would not fit renders it in depth-ordered chunks (SceneStorage).
    uint64_t memory_budget = 0;
    // Keep what the driver says of every pipeline compiled on this context (registers, shared
    // memory, binary size: the names and values are the driver's own), where it can say
    // (DeviceInfo::pipeline_statistics); see Context::pipeline_statistics(). For tuning shaders:
    // a pass's occupancy follows from its registers and shared memory.
    bool pipeline_statistics = false;
};

// What the driver says of one compiled pipeline (VK_KHR_pipeline_executable_properties).
struct PipelineStatistics {
    std::string pipeline;  // vksplat's name for it ("blend", "radix_scatter", ...)
    std::vector<std::pair<std::string, std::string>> values;  // statistic and its value as text
};

// An application's Vulkan objects, lent to vksplat (see Context(const AdoptedDevice&)). The
// application keeps ownership: vksplat never destroys them, and they must outlive the Context and
// everything made from it. What the device must have been created with:
//   - Vulkan 1.2 or newer (VkApplicationInfo::apiVersion and the device's own version);
//   - VkPhysicalDeviceVulkan12Features::bufferDeviceAddress (every pass addresses its buffers so);
//   - optionally shaderInt64 + shaderBufferInt64Atomics, for per-Gaussian statistics only.
// The physical device must pass the checks list_devices() reports (subgroup ballot and arithmetic).
struct AdoptedDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queue_family = 0;  // must support compute; command buffers given to vksplat come from it
    // A queue of queue_family. vksplat submits its own one-off work here (scene upload, and
    // Renderer::render), and waits on it when its buffers must grow, so the application must not
    // use this queue from another thread while it calls into vksplat (Vulkan's external
    // synchronisation rule for queues).
    VkQueue queue = VK_NULL_HANDLE;
    // The application's loader entry point, so vksplat calls the same loader (and layers) the
    // application does. Null: vksplat opens the system loader, libvulkan.so.1.
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    // Set if the device was created with shaderInt64 and shaderBufferInt64Atomics.
    bool int64_atomics_enabled = false;
    // Set if the device was created with VK_EXT_shader_atomic_float's shaderBufferFloat32AtomicAdd.
    bool float_atomics_enabled = false;
};

// Every physical device, with whether vksplat can use it.
std::vector<DeviceInfo> list_devices();

// Whether VK_LAYER_KHRONOS_validation is installed, i.e. whether ContextOptions::validation can be
// honoured (Debian: vulkan-validationlayers). Throws GpuError when there is no Vulkan loader.
bool validation_layer_installed();

class Context {
public:
    // Creates and owns an instance and a device.
    explicit Context(const ContextOptions& options = {});
    // Works on the application's device; destroys nothing of it (not even waiting for it to go
    // idle). vksplat loads its own table of the device's entry points through volk, so the
    // application's function pointers, or its own volk, are left as they are. Throws GpuError if the
    // physical device cannot run vksplat or the queue family has no compute.
    explicit Context(const AdoptedDevice& adopted);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const;
    VkPhysicalDevice physical_device() const;
    VkDevice device() const;
    VkQueue queue() const;
    uint32_t queue_family() const;
    const DeviceInfo& info() const;
    // ContextOptions::memory_budget, or the device's own limit when that is 0 (adopted devices too).
    uint64_t memory_budget() const;
    // False for an adopted device.
    bool owns_device() const;
    // Validation messages (errors and warnings) seen so far; empty unless validation is on.
    std::vector<std::string> validation_messages() const;
    // Every pipeline compiled on this context so far, in order; empty unless
    // ContextOptions::pipeline_statistics was set and the driver offers them.
    std::vector<PipelineStatistics> pipeline_statistics() const;

    // Device memory of the buffers vksplat holds on this context now (MemoryKind::device, as
    // allocated: sizes rounded up to the driver's alignment), and the most it has held since the
    // context was made or since the last reset_peak_device_bytes(). Transients count: a buffer that
    // lives for one pass raises the peak as much as one that lives for the whole run.
    uint64_t held_device_bytes() const;
    uint64_t peak_device_bytes() const;
    // Starts the peak over from what is held now (to measure one job of several on a context).
    void reset_peak_device_bytes() const;

    struct Impl;
    Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vksplat::gpu
