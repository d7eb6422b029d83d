// Embedding vksplat in an application that owns its Vulkan objects.
//
// The application (this file) creates the instance, device, queue, a command buffer and the images
// and buffers it wants the picture in, using the system Vulkan loader directly. It lends them to
// vksplat (gpu::AdoptedDevice), records vksplat's render into its own command buffer, submits it
// itself, reads back its own image and buffer, and checks every pixel against vksplat's ordinary
// render() of the same view. Exits 0 when they agree, 1 when they do not.
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <vksplat/scene/demo_scene.hpp>
#include <vksplat/render/renderer.hpp>

namespace {

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(result));
}

// The application's own Vulkan objects: nothing here belongs to vksplat.
struct App {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;

    App() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "vksplat embed example";
        app.apiVersion = VK_API_VERSION_1_2;  // vksplat needs 1.2
        VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        instance_info.pApplicationInfo = &app;
        check(vkCreateInstance(&instance_info, nullptr, &instance), "vkCreateInstance");

        // The first device with a compute queue family. (A real application picks its own way; the
        // Context constructor refuses a device vksplat cannot use.)
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        for (VkPhysicalDevice candidate : devices) {
            uint32_t families = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
            std::vector<VkQueueFamilyProperties> properties(families);
            vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, properties.data());
            for (uint32_t f = 0; f < families && !physical; ++f)
                if (properties[f].queueFlags & VK_QUEUE_COMPUTE_BIT) physical = candidate, family = f;
            if (physical) break;
        }
        if (!physical) throw std::runtime_error("no Vulkan device with a compute queue");

        // What vksplat needs of the device: buffer device addresses (Vulkan 1.2 core).
        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.bufferDeviceAddress = VK_TRUE;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue_info.queueFamilyIndex = family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        device_info.pNext = &features12;
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        check(vkCreateDevice(physical, &device_info, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);

        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.queueFamilyIndex = family;
        check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(vkCreateFence(device, &fence_info, nullptr, &fence), "vkCreateFence");
    }
    ~App() {
        vkDeviceWaitIdle(device);
        vkDestroyFence(device, fence, nullptr);
        vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
        vkDestroyInstance(instance, nullptr);
    }

    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const {
        VkPhysicalDeviceMemoryProperties memory;
        vkGetPhysicalDeviceMemoryProperties(physical, &memory);
        for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
        throw std::runtime_error("no suitable memory type");
    }

    // Records with `record`, submits, and waits: the application's frame.
    template <class Record>
    void run_frame(Record record) {
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VkCommandBuffer cb;
        check(vkAllocateCommandBuffers(device, &alloc, &cb), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
        record(cb);
        check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cb;
        check(vkResetFences(device, 1, &fence), "vkResetFences");
        check(vkQueueSubmit(queue, 1, &submit, fence), "vkQueueSubmit");
        check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vkFreeCommandBuffers(device, pool, 1, &cb);
    }
};

struct HostBuffer {
    const App& app;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    HostBuffer(const App& a, VkDeviceSize size) : app(a) {
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = size;
        info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        check(vkCreateBuffer(app.device, &info, nullptr, &buffer), "vkCreateBuffer");
        VkMemoryRequirements needs;
        vkGetBufferMemoryRequirements(app.device, buffer, &needs);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = needs.size;
        alloc.memoryTypeIndex = app.memory_type(needs.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                          VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        check(vkAllocateMemory(app.device, &alloc, nullptr, &memory), "vkAllocateMemory");
        check(vkBindBufferMemory(app.device, buffer, memory, 0), "vkBindBufferMemory");
        check(vkMapMemory(app.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    }
    ~HostBuffer() {
        vkDestroyBuffer(app.device, buffer, nullptr);
        vkFreeMemory(app.device, memory, nullptr);
    }
};

struct Image {
    const App& app;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    Image(const App& a, uint32_t width, uint32_t height, VkFormat format) : app(a) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {width, height, 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        check(vkCreateImage(app.device, &info, nullptr, &image), "vkCreateImage");
        VkMemoryRequirements needs;
        vkGetImageMemoryRequirements(app.device, image, &needs);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = needs.size;
        alloc.memoryTypeIndex = app.memory_type(needs.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        check(vkAllocateMemory(app.device, &alloc, nullptr, &memory), "vkAllocateMemory");
        check(vkBindImageMemory(app.device, image, memory, 0), "vkBindImageMemory");
    }
    ~Image() {
        vkDestroyImage(app.device, image, nullptr);
        vkFreeMemory(app.device, memory, nullptr);
    }
};

// Largest difference, in 8-bit levels, between the packed pixels and the float render.
int max_level_difference(const uint8_t* packed, const vksplat::RenderOutput& expected, bool bgra) {
    int worst = 0;
    for (size_t i = 0; i < expected.alpha.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            const float value = c < 3 ? expected.rgb[i * 3 + c] : expected.alpha[i];
            const int level = int(std::lround(std::fmin(std::fmax(value, 0.0f), 1.0f) * 255.0f));
            const int channel = bgra && c < 3 ? 2 - c : c;
            worst = std::max(worst, std::abs(level - int(packed[i * 4 + channel])));
        }
    return worst;
}

}  // namespace

int main() {
    try {
        const int width = 96, height = 64;
        const vksplat::GaussianCloud scene = vksplat::make_demo_scene();
        const auto cameras = vksplat::make_orbit_cameras(2, width, height, 4.0, 30.0);
        vksplat::RenderSettings settings;
        settings.background = {0.1f, 0.2f, 0.3f};

        // What vksplat renders on its own device: the expected pictures.
        std::vector<vksplat::RenderOutput> expected;
        {
            vksplat::gpu::Context own;
            vksplat::Renderer renderer(own);
            renderer.set_scene(scene);
            for (const auto& camera : cameras) expected.push_back(renderer.render(camera, settings));
        }

        App app;
        int failures = 0;
        {
            vksplat::gpu::AdoptedDevice lent;
            lent.instance = app.instance;
            lent.physical_device = app.physical;
            lent.device = app.device;
            lent.queue_family = app.family;
            lent.queue = app.queue;
            lent.get_instance_proc_addr = vkGetInstanceProcAddr;  // our loader, so vksplat sees our layers
            vksplat::gpu::Context context(lent);
            vksplat::Renderer renderer(context);
            renderer.set_scene(scene);

            // Frame 1: into our 8-bit BGRA image, left ready for a transfer, which copies it out.
            Image image(app, width, height, VK_FORMAT_B8G8R8A8_UNORM);
            HostBuffer image_pixels(app, VkDeviceSize(width) * height * 4);
            app.run_frame([&](VkCommandBuffer cb) {
                renderer.record(cb, cameras[0], settings,
                                vksplat::RenderTarget::to_image(image.image, VK_FORMAT_B8G8R8A8_UNORM,
                                                                VK_IMAGE_LAYOUT_UNDEFINED,
                                                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
                VkBufferImageCopy region{};
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                region.imageExtent = {uint32_t(width), uint32_t(height), 1};
                vkCmdCopyImageToBuffer(cb, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image_pixels.buffer, 1,
                                       &region);
                VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
                to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
                vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                                     nullptr, 0, nullptr);
            });
            const int image_difference =
                max_level_difference(static_cast<const uint8_t*>(image_pixels.mapped), expected[0], true);
            std::printf("image target (B8G8R8A8_UNORM): max difference %d levels\n", image_difference);
            failures += image_difference > 1;

            // Frame 2: another view, as floats into our host-visible buffer.
            HostBuffer floats(app, VkDeviceSize(width) * height * 16);
            app.run_frame([&](VkCommandBuffer cb) {
                renderer.record(cb, cameras[1], settings,
                                vksplat::RenderTarget::to_buffer(floats.buffer, VK_FORMAT_R32G32B32A32_SFLOAT));
                VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
                to_host.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
                to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
                vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host,
                                     0, nullptr, 0, nullptr);
            });
            const auto* got = static_cast<const float*>(floats.mapped);
            float float_difference = 0;
            double coverage = 0;
            for (size_t i = 0; i < expected[1].alpha.size(); ++i) {
                for (int c = 0; c < 3; ++c)
                    float_difference = std::fmax(float_difference, std::fabs(got[i * 4 + c] - expected[1].rgb[i * 3 + c]));
                float_difference = std::fmax(float_difference, std::fabs(got[i * 4 + 3] - expected[1].alpha[i]));
                coverage += got[i * 4 + 3];
            }
            coverage /= double(expected[1].alpha.size());
            std::printf("buffer target (R32G32B32A32_SFLOAT): max difference %.3g, %.1f%% covered\n", float_difference,
                        coverage * 100);
            failures += float_difference > 1e-4f || coverage < 0.05;
            std::printf("last recorded frame: %u of %u Gaussians visible, %u tile entries\n",
                        renderer.last_frame().visible, renderer.last_frame().gaussians,
                        renderer.last_frame().tile_entries);
        }  // the Renderer and Context go first; the application's device is still alive below
        if (vkDeviceWaitIdle(app.device) != VK_SUCCESS) {
            std::printf("the application's device was harmed\n");
            ++failures;
        }
        std::printf(failures ? "embed: FAILED\n" : "embed: the application's frame matches vksplat's render\n");
        return failures ? 1 : 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
}
