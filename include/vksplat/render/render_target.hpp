#pragma once
// Rendering into an application's own Vulkan frame: Renderer::record() records one view into a
// command buffer the application is recording, and leaves the picture in an image or buffer the
// application owns.
//
//   gpu::AdoptedDevice lent{instance, physical_device, device, family, queue};
//   gpu::Context context(lent);                 // borrows; destroys nothing of the application's
//   Renderer renderer(context);
//   renderer.set_scene(cloud);
//   ... vkBeginCommandBuffer(cmd) ...
//   renderer.record(cmd, camera, settings, RenderTarget::to_image(image, VK_FORMAT_B8G8R8A8_UNORM,
//                   VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
//   ... blit or sample the image, vkEndCommandBuffer(cmd), vkQueueSubmit(queue, ...) ...
//
// Synchronisation contract of Renderer::record()
// -----------------------------------------------
// What vksplat waits on and signals: nothing. It creates no semaphore or fence and never begins,
// ends or submits the application's command buffer. Ordering with the rest of the application's
// frame comes from submission order on the queue plus the barriers below; the application's own
// semaphores (e.g. swapchain acquire/present) stay the application's.
//
// Barriers it records, in order:
//   1. On entry, one global memory barrier
//        src: ALL_COMMANDS, MEMORY_WRITE
//        dst: COMPUTE_SHADER | DRAW_INDIRECT | TRANSFER,
//             SHADER_READ | SHADER_WRITE | INDIRECT_COMMAND_READ | TRANSFER_READ | TRANSFER_WRITE
//      so the render starts after all earlier work on the queue: previous frames still using
//      vksplat's own buffers, and the application's writes to the target buffer.
//   2. Between its passes, global memory barriers from COMPUTE_SHADER | TRANSFER writes to
//      COMPUTE_SHADER | DRAW_INDIRECT | TRANSFER reads and writes. They touch only vksplat's buffers.
//   3. For an image target, one image memory barrier (colour aspect, mip 0, layer 0)
//        old_layout -> TRANSFER_DST_OPTIMAL
//        src: ALL_COMMANDS, MEMORY_READ | MEMORY_WRITE   dst: TRANSFER, TRANSFER_WRITE
//      then vkCmdCopyBufferToImage of the camera's width x height at (0, 0), then
//        TRANSFER_DST_OPTIMAL -> final_layout
//        src: TRANSFER, TRANSFER_WRITE                   dst: ALL_COMMANDS, MEMORY_READ | MEMORY_WRITE
//      An old_layout of UNDEFINED discards the image's contents (fine when all of it is overwritten).
//   3'. For a buffer target, vkCmdCopyBuffer into [offset, offset + width * height * bytes per pixel),
//      then one buffer memory barrier over that range
//        src: TRANSFER, TRANSFER_WRITE                   dst: ALL_COMMANDS, MEMORY_READ | MEMORY_WRITE
//   4. Last, a copy of its frame counters to host memory and a TRANSFER_WRITE -> HOST_READ barrier.
// Queue family ownership is never transferred: the target must be usable by the context's queue
// family (created by it, or VK_SHARING_MODE_CONCURRENT including it).
//
// What the application must do:
//   - record into a primary command buffer of the context's queue family, outside a render pass,
//     and submit it to the context's queue (vksplat's barriers order it after earlier submissions
//     there, and it is the queue vksplat waits on) before calling record() again;
//   - create the target with VK_IMAGE_USAGE_TRANSFER_DST_BIT / VK_BUFFER_USAGE_TRANSFER_DST_BIT,
//     at least the camera's width x height (a buffer: from `offset`, tightly packed rows);
//   - keep the Renderer alive until the GPU has finished every command buffer it recorded into. The
//     Renderer's destructor and set_scene() wait for the context's queue to go idle if record() was
//     ever called, so that they free nothing a pending frame still reads; so does record() itself
//     when a larger image, a larger scene or a denser view makes it grow its buffers.
//
// Tile-entry capacity: a frame recorded here cannot grow its buffers and re-run as render() does.
// record() reads the counters of the last recorded frame that completed; if that frame needed more
// tile entries than it had, the buffers grow (after waiting for the queue) before this frame is
// recorded. A view much denser than any before may therefore miss splats for one frame. To avoid
// even that, call render_gpu_only(camera) once first: it sizes the buffers for that view.
#include <vulkan/vulkan_core.h>

#include <cstdint>

namespace vksplat {

struct RenderTarget {
    // Where the picture goes: exactly one of `image` and `buffer` is set.
    VkImage image = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;  // buffer only: where the first pixel goes
    // The pixel layout written, row-major, top row first:
    //   VK_FORMAT_R32G32B32A32_SFLOAT: the renderer's floats as they are (rgb unclamped, alpha);
    //   VK_FORMAT_R8G8B8A8_UNORM / _SRGB, VK_FORMAT_B8G8R8A8_UNORM / _SRGB: each value clamped to
    //   [0, 1] and rounded to 8 bits, in that byte order. The values are written as they are for the
    //   _SRGB formats too: 3DGS colours are already display-encoded, as the photos they fit were.
    // Alpha is 1 - T, the coverage (colour already holds background * T).
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;               // image only: layout on entry
    VkImageLayout final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // image only: layout on exit

    static RenderTarget to_image(VkImage image, VkFormat format, VkImageLayout old_layout,
                                 VkImageLayout final_layout) {
        RenderTarget target;
        target.image = image;
        target.format = format;
        target.old_layout = old_layout;
        target.final_layout = final_layout;
        return target;
    }
    static RenderTarget to_buffer(VkBuffer buffer, VkFormat format, VkDeviceSize offset = 0) {
        RenderTarget target;
        target.buffer = buffer;
        target.format = format;
        target.offset = offset;
        return target;
    }
};

// Bytes one pixel of `format` takes (16 or 4); 0 for a format record() does not write.
uint32_t render_target_pixel_bytes(VkFormat format);

}  // namespace vksplat
