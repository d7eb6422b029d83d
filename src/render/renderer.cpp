#include "vksplat/render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <deque>
#include <optional>
#include <stdexcept>

#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "gpu/context_impl.hpp"
#include "gpu/prefix_scan.hpp"
#include "render/entry_growth.hpp"
#include "render/frame_layout.hpp"
#include "render/frame_resources.hpp"
#include "render/gpu_scene.hpp"
#include "render/scene_chunks.hpp"
#include "render/stats_totals.hpp"
#include "render/target_copy.hpp"
#include "render/tile_binning.hpp"
#include "shaders/render/blend.kernel.hpp"
#include "shaders/render/blend_carry.kernel.hpp"
#include "shaders/render/blend_stats.kernel.hpp"
#include "shaders/render/blend_stats_carry.kernel.hpp"
#include "shaders/render/pack_rgba8.kernel.hpp"
#include "vksplat/error.hpp"

namespace vksplat {
namespace {

std::string mebibytes(uint64_t bytes) {
    if (bytes < (1 << 20)) return std::to_string(bytes) + " bytes";
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / (1 << 20));
    return text;
}

// Refuses a frame that needs more than `budget` even with a single Gaussian: `least` bytes, of
// which `image` grow with its pixels. Chunks split the Gaussians, never the pixels, so the message
// says what the frame itself needs, and advises a larger budget only where the device has one.
void check_frame_fits(const Camera& camera, uint64_t least, uint64_t image, uint64_t budget, uint64_t device) {
    if (least <= budget) return;
    const uint64_t pixels = uint64_t(camera.width) * uint64_t(camera.height);
    const std::string frame = "a " + std::to_string(camera.width) + "x" + std::to_string(camera.height) + " frame";
    const std::string needs = mebibytes(least) + " however the Gaussians are chunked (its per-pixel buffers: " +
                              std::to_string(image / pixels) + " bytes a pixel, " + mebibytes(image) + ")";
    if (device > 0 && least > device)
        throw GpuError(frame + " needs " + needs + ": more than the device's " + mebibytes(device) +
                       "; use a smaller resolution");
    throw GpuError("memory budget of " + mebibytes(budget) + " is too small for " + frame + ": it needs " + needs +
                   "; raise --memory-budget to at least " + std::to_string((least + (1 << 20) - 1) >> 20) + " (MiB" +
                   (device > 0 ? "; the device has " + mebibytes(device) : std::string()) + ")");
}

// One view's statistics (indexed like the input cloud) into totals over views, as
// shaders/render/stats_totals.comp adds them on the device.
void add_view(GaussianTotals& totals, const GaussianStats& stats) {
    for (size_t i = 0; i < totals.size(); ++i) {
        totals.blend_weight[i] += stats.blend_weight[i];
        totals.max_weight[i] = std::max(totals.max_weight[i], stats.max_weight[i]);
        totals.pixels[i] += stats.pixels[i];
        if (!stats.visible[i]) continue;
        const auto radius = uint64_t(std::min(stats.radius[i], float(shader::render::TOTALS_MAX_RADIUS)));
        totals.radius_squared[i] += radius * radius;
        ++totals.views_visible[i];
    }
}

}  // namespace

struct Renderer::Impl {
    const gpu::Context& context;
    render::TileBinning binning;
    // The blend variants (shaders/render/blend.h) and the 8-bit packing (shaders/render/pack_rgba8.h).
    gpu::Kernel<shader::render::BlendKernel> blend;
    gpu::CommandStream stream;
    std::unique_ptr<gpu::Kernel<shader::render::BlendStatsKernel>> blend_stats;  // built on first use
    std::unique_ptr<gpu::Kernel<shader::render::PackRgba8Kernel>> pack_rgba8;  // built on the first record() to an 8-bit target
    // Built on first use (chunked frames).
    std::unique_ptr<gpu::Kernel<shader::render::BlendCarryKernel>> blend_carry;
    std::unique_ptr<gpu::Kernel<shader::render::BlendStatsCarryKernel>> blend_stats_carry;
    // Built on first use (render_stats_totals).
    std::unique_ptr<gpu::Kernel<shader::render::StatsTotalsKernel>> stats_totals;
    bool recorded = false;                               // record() was called: frames may be in flight
    render::GpuScene scene;  // params and sh are empty while the scene lives on the host only (chunked frames)
    // Device memory the renderer may hold (SceneStorage::memory_budget, else the context's).
    uint64_t budget = 0;
    // The activated scene in host memory, kept when a frame may have to be split into chunks
    // (the scene did not fit the budget, or the budget was set explicitly); else empty.
    render::HostScene host;
    bool has_host = false;
    std::unique_ptr<render::SceneChunks> chunks;  // device buffers for one chunk (chunked frames)
    double chunk_entries_per_gaussian = render::kInitialEntriesPerGaussian;  // learnt by chunked frames
    size_t input_count = 0;                // Gaussians in the cloud given to set_scene
    std::vector<uint32_t> kept_indices;     // input index of each uploaded Gaussian, if any were dropped
    render::FrameResources frame;
    FrameStats stats;

    explicit Impl(const gpu::Context& c)
        : context(c),
          binning(c),
          blend(c),
          stream(c),
          frame(c) {}

    // Everything from the per-frame parameters to the blended image of `source` (the scene, or one
    // chunk of it), recorded into `stream`: the passes up to the tile ranges, then the blend.
    void record_passes(gpu::CommandStream& stream, const render::CameraParams& params, const render::GpuScene& source,
                       bool gather_stats);
    void record_tiles(gpu::CommandStream& stream, const render::CameraParams& params, const render::GpuScene& source,
                      bool gather_stats);
    // With carry_flags (shaders/render/blend.h's CARRY_ flags) the blend continues from, and except for
    // the last chunk stores, the carried pixel state.
    void record_blend_pass(gpu::CommandStream& stream, uint32_t tiles_x, uint32_t tiles_y, bool gather_stats,
                           const uint32_t* carry_flags = nullptr);
    // With `totals`, the statistics are added into them on the device instead of read back.
    void record_frame(const render::CameraParams& params, bool read_back, bool gather_stats,
                      render::StatsTotals* totals = nullptr);
    // The image readback: colour and alpha (16 bytes a pixel), depth (4), contributors (4), then
    // the counters; without the image (read_back false) the counters alone, at offset 0.
    static VkDeviceSize readback_counters_offset(uint32_t pixels, bool read_back) {
        return read_back ? uint64_t(pixels) * 24 : 0;
    }
    void copy_image_to_readback(gpu::CommandStream& stream, uint32_t pixels);
    void record_into(VkCommandBuffer command_buffer, const Camera& camera, const RenderSettings& settings,
                     const RenderTarget& target);
    const gpu::Kernel<shader::render::PackRgba8Kernel>& pack_kernel();
    // Waits for the frames recorded into the application's command buffers, before a buffer they
    // use is freed. Nothing to wait for if record() was never called.
    void wait_for_recorded_frames() const;
    // `totals` (statistics summed on the device, for a scene without a host copy: such a frame is
    // never chunked) instead of `gathered`.
    void run(const Camera& camera, const RenderSettings& settings, bool read_back,
             render::StatsTotals* totals = nullptr);
    // The frame with the whole scene on the device; false (having drawn nothing) when its tile
    // entries would outgrow the memory budget and the frame can go in chunks instead.
    bool run_whole(const Camera& camera, const RenderSettings& settings, bool read_back,
                   render::StatsTotals* totals = nullptr);
    // The frame in depth-ordered chunks uploaded from `host`, each within the memory budget.
    void run_chunked(const Camera& camera, const RenderSettings& settings, bool read_back);
    // Device bytes after ensure_* for these sizes, given what the frame resources already hold.
    uint64_t projected_frame_bytes(uint32_t gaussians, uint32_t entries, uint32_t pixels, uint32_t tiles, bool carry,
                                   bool gather_stats) const;
    uint64_t scene_device_bytes() const;
    const gpu::Kernel<shader::render::BlendCarryKernel>& carry_kernel();
    const gpu::Kernel<shader::render::BlendStatsCarryKernel>& stats_carry_kernel();
    void add_stage_times();
    const gpu::Kernel<shader::render::BlendStatsKernel>& stats_kernel();
    std::vector<uint32_t> stats_specialization() const;
    // Per-Gaussian statistics of `count` Gaussians to the readback, and from there into `out`
    // (indexed like the input cloud), Gaussian i of the frame being the scene's uploaded[i]
    // (i itself where uploaded is null).
    void copy_stats(gpu::CommandStream& stream, uint32_t count);
    void unpack_stats(uint32_t count, const uint32_t* uploaded, GaussianStats& out) const;
    GaussianStats gathered;  // the last frame's statistics
};

// blend_body.glsl's SUM_IN_SUBGROUP: sum a subgroup's statistics before the atomics, except on a
// CPU implementation, where the atomics are the cheaper of the two.
std::vector<uint32_t> Renderer::Impl::stats_specialization() const {
    return {context.info().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0u : 1u};
}

const gpu::Kernel<shader::render::BlendStatsKernel>& Renderer::Impl::stats_kernel() {
    if (!blend_stats) {
        if (!context.info().int64_atomics)
            throw GpuError("per-Gaussian statistics need 64-bit buffer atomics, which " + context.info().name +
                           " does not offer");
        blend_stats = std::make_unique<gpu::Kernel<shader::render::BlendStatsKernel>>(context, stats_specialization());
    }
    return *blend_stats;
}

void Renderer::Impl::record_passes(gpu::CommandStream& stream, const render::CameraParams& params,
                                   const render::GpuScene& source, bool gather_stats) {
    record_tiles(stream, params, source, gather_stats);
    record_blend_pass(stream, params.size[2], params.size[3], gather_stats);
}

void Renderer::Impl::record_tiles(gpu::CommandStream& stream, const render::CameraParams& params,
                                  const render::GpuScene& source, bool gather_stats) {
    auto& f = frame;
    if (gather_stats) {
        stream.fill(f.stat_weight, 0);
        stream.fill(f.stat_max_weight, 0);
        stream.fill(f.stat_pixels, 0);
        stream.fill(f.stat_centre_weight, 0);
    }
    binning.record(stream, f, params, {source.params.address(), source.sh.address(), source.count});
}

void Renderer::Impl::record_blend_pass(gpu::CommandStream& stream, uint32_t tiles_x, uint32_t tiles_y,
                                       bool gather_stats, const uint32_t* carry_flags) {
    using namespace shader::render;
    auto& f = frame;
    // Every variant's push starts with the frame's buffers (shaders/render/blend.h).
    const BlendFrame buffers = render::blend_frame(f);
    const BlendStats stats{.stat_weight = f.stat_weight.address(),
                           .stat_max_weight = f.stat_max_weight.address(),
                           .stat_pixels = f.stat_pixels.address(),
                           .stat_centre_weight = f.stat_centre_weight.address()};
    if (carry_flags) {
        const BlendCarry carry{.carried_color = f.carried_color.address(),
                               .carried_depth_count = f.carried_depth_count.address(),
                               .carry_flags = *carry_flags};
        if (gather_stats)
            stream.dispatch(stats_carry_kernel(), {.blend = buffers, .stats = stats, .carry = carry}, tiles_x, tiles_y);
        else
            stream.dispatch(carry_kernel(), {.blend = buffers, .carry = carry}, tiles_x, tiles_y);
    } else if (gather_stats) {
        stream.dispatch(*blend_stats, {.blend = buffers, .stats = stats}, tiles_x, tiles_y);
    } else
        stream.dispatch(blend, {.blend = buffers}, tiles_x, tiles_y);
    stream.barrier();
    stream.mark("blend");
}

void Renderer::Impl::record_frame(const render::CameraParams& params, bool read_back, bool gather_stats,
                                  render::StatsTotals* totals) {
    const uint32_t pixels = params.size[0] * params.size[1];
    const uint32_t n = scene.count;
    auto& f = frame;
    stream.begin();
    record_passes(stream, params, scene, gather_stats);
    if (gather_stats && totals)
        totals->record_add(stream, f, f.entry_capacity);
    else if (gather_stats)
        copy_stats(stream, n);

    const VkDeviceSize counters_offset = readback_counters_offset(pixels, read_back);
    if (read_back) copy_image_to_readback(stream, pixels);
    stream.copy(f.counters, f.readback, render::kCounterCount * sizeof(uint32_t), 0, counters_offset);
    stream.submit_and_wait();
}

void Renderer::Impl::copy_image_to_readback(gpu::CommandStream& stream, uint32_t pixels) {
    auto& f = frame;
    stream.copy(f.color_alpha, f.readback, uint64_t(pixels) * 16, 0, 0);
    stream.copy(f.depth, f.readback, uint64_t(pixels) * 4, 0, uint64_t(pixels) * 16);
    stream.copy(f.contributors, f.readback, uint64_t(pixels) * 4, 0, uint64_t(pixels) * 20);
}

uint64_t Renderer::Impl::scene_device_bytes() const {
    return scene.params.size() + scene.sh.size() + (chunks ? chunks->device.params.size() + chunks->device.sh.size() : 0);
}

uint64_t Renderer::Impl::projected_frame_bytes(uint32_t gaussians, uint32_t entries, uint32_t pixels, uint32_t tiles,
                                               bool carry, bool gather_stats) const {
    const auto& f = frame;
    const uint32_t carried = std::max(carry ? pixels : 0u, f.carry_capacity);
    const uint64_t stats_count = std::max(gather_stats ? std::max(gaussians, 1u) : 0u, f.stats_capacity);
    return render::FrameResources::bytes_for(context, std::max(gaussians, f.gaussian_capacity),
                                             std::max(entries, f.entry_capacity), std::max(pixels, f.pixel_capacity),
                                             std::max(tiles, f.tile_capacity), false) +
           uint64_t(carried) * render::FrameResources::kCarryBytesPerPixel +
           stats_count * render::FrameResources::kStatsBytesPerGaussian + f.packed.size();
}

const gpu::Kernel<shader::render::BlendStatsCarryKernel>& Renderer::Impl::stats_carry_kernel() {
    stats_kernel();  // the same device check
    if (!blend_stats_carry)
        blend_stats_carry =
            std::make_unique<gpu::Kernel<shader::render::BlendStatsCarryKernel>>(context, stats_specialization());
    return *blend_stats_carry;
}

const gpu::Kernel<shader::render::BlendCarryKernel>& Renderer::Impl::carry_kernel() {
    if (!blend_carry) blend_carry = std::make_unique<gpu::Kernel<shader::render::BlendCarryKernel>>(context);
    return *blend_carry;
}

void Renderer::Impl::add_stage_times() {
    for (const auto& t : stream.stage_times()) {
        auto same = std::find_if(stats.stages.begin(), stats.stages.end(),
                                 [&](const StageTiming& s) { return s.stage == t.label; });
        if (same == stats.stages.end())
            stats.stages.push_back({t.label, t.milliseconds});
        else
            same->milliseconds += t.milliseconds;
        stats.gpu_milliseconds += t.milliseconds;
    }
}

void Renderer::Impl::run(const Camera& camera, const RenderSettings& settings, bool read_back,
                         render::StatsTotals* totals) {
    if (totals && has_host) throw std::logic_error("Renderer: device totals of a scene that may be chunked");
    camera.validate();
    const auto [pixels, tiles] = render::image_extent(camera);
    // The image buffers of a frame no device can hold: refused before an allocation fails with
    // advice (a smaller budget, chunks) that cannot help.
    const uint64_t device = context.info().device_local_budget;
    const uint64_t image = render::FrameResources::image_bytes(pixels, tiles, false);
    if (device > 0) check_frame_fits(camera, image, image, device, device);
    stats = {};
    stats.gaussians = scene.count;
    if (scene.params) {
        const uint32_t entries =
            std::max(frame.entry_capacity, std::max(scene.count, 1u) * render::kInitialEntriesPerGaussian);
        const uint64_t need = scene_device_bytes() +
                              projected_frame_bytes(scene.count, entries, pixels, tiles, false, settings.gather_stats);
        // Without a host copy there is nothing to chunk from: the budget is then the device's own
        // limit, and a frame beyond it fails with the allocation's out-of-memory message.
        if ((need <= budget || !has_host) && run_whole(camera, settings, read_back, totals)) return;
        // From here on the scene lives on the host: free its device copy for the chunks.
        scene.params = gpu::Buffer();
        scene.sh = gpu::Buffer();
    }
    run_chunked(camera, settings, read_back);
}

bool Renderer::Impl::run_whole(const Camera& camera, const RenderSettings& settings, bool read_back,
                               render::StatsTotals* totals) {
    const auto [pixels, tiles] = render::image_extent(camera);
    frame.ensure_gaussians(scene.count);
    frame.ensure_image(pixels, tiles);
    frame.ensure_readback(pixels);
    if (frame.entry_capacity == 0) frame.ensure_entries(std::max(scene.count, 1u) * render::kInitialEntriesPerGaussian);
    if (settings.gather_stats) {
        stats_kernel();
        frame.ensure_stats(scene.count);
    }

    for (;;) {
        const auto params = render::make_camera_params(camera, settings, scene.count, scene.sh_degree,
                                                       scene.half_sh, frame.entry_capacity);
        stats.tile_key_bits = render::tile_key_bits(params.size[2] * params.size[3]);
        record_frame(params, read_back, settings.gather_stats, totals);
        uint32_t counters[render::kCounterCount];
        const VkDeviceSize counters_offset = readback_counters_offset(pixels, read_back);
        std::memcpy(counters, static_cast<const char*>(frame.readback.mapped()) + counters_offset, sizeof(counters));
        stats.visible = counters[render::kCounterVisible];
        stats.tile_entries = counters[render::kCounterEntriesNeeded];
        // Before the capacity test: a saturated count may be below a capacity grown for an earlier view.
        render::check_entries_sortable(stats.tile_entries);
        if (stats.tile_entries <= frame.entry_capacity) break;
        // The view needs more tile entries than the buffers hold: grow with headroom and redo it.
        render::check_frame_attempts(stats.attempts, "view '" + camera.name + "'");
        const uint32_t grown = render::grown_entry_capacity(stats.tile_entries);
        if (has_host && scene_device_bytes() + projected_frame_bytes(scene.count, grown, pixels, tiles, false,
                                                                     settings.gather_stats) > budget) {
            stats = {};
            stats.gaussians = scene.count;
            return false;
        }
        frame.ensure_entries(grown);
        ++stats.attempts;
    }
    add_stage_times();
    if (settings.gather_stats && !totals) {
        gathered = {};
        gathered.resize(input_count);
        unpack_stats(scene.count, nullptr, gathered);
    }
    stats.scene_bytes = scene_device_bytes();
    stats.device_bytes = frame.device_bytes() + stats.scene_bytes;
    return true;
}

void Renderer::Impl::run_chunked(const Camera& camera, const RenderSettings& settings, bool read_back) {
    const auto [pixels, tiles] = render::image_extent(camera);
    const int degree = scene.sh_degree;
    const bool half = scene.half_sh;
    const bool with_stats = settings.gather_stats;
    if (with_stats) stats_carry_kernel();  // fails early on a device without 64-bit atomics

    // Device bytes for a chunk of g Gaussians with e tile entries, from fresh buffers.
    const auto need = [&](uint32_t g, uint32_t e) {
        return render::GpuScene::bytes_for(g, degree, half) +
               render::FrameResources::bytes_for(context, g, e, pixels, tiles, true) +
               (with_stats ? uint64_t(std::max(g, 1u)) * render::FrameResources::kStatsBytesPerGaussian : 0);
    };
    const auto entries_for = [&](uint32_t g) {
        return static_cast<uint32_t>(std::min(std::ceil(g * chunk_entries_per_gaussian), double(0x7fffffffu)));
    };
    check_frame_fits(camera, need(1, entries_for(1)), render::FrameResources::image_bytes(pixels, tiles, true), budget,
                     context.info().device_local_budget);

    const auto order = render::depth_order(host, render::make_camera_params(camera, settings, 0, degree, half, 0));
    const uint32_t drawable = static_cast<uint32_t>(order.size());
    // The largest chunk that fits, then chunks of equal size.
    uint32_t lo = 1, hi = std::max(drawable, 1u);
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo + 1) / 2;
        if (need(mid, entries_for(mid)) <= budget) lo = mid;
        else hi = mid - 1;
    }
    const uint32_t chunk_count = (drawable + lo - 1) / lo;
    const uint32_t chunk_size = chunk_count > 0 ? (drawable + chunk_count - 1) / chunk_count : 0;

    // Buffers for that chunk size; start afresh if what is held already would exceed the budget.
    const auto held_with = [&](uint32_t gaussians, uint32_t entries) {
        return render::GpuScene::bytes_for(std::max(gaussians, chunks ? chunks->capacity : 0u), degree, half) +
               projected_frame_bytes(gaussians, entries, pixels, tiles, true, with_stats);
    };
    if (held_with(chunk_size, entries_for(chunk_size)) > budget) {
        chunks.reset();
        frame = render::FrameResources(context);
    }
    if (!chunks || chunks->capacity < chunk_size) {
        chunks.reset();
        chunks = std::make_unique<render::SceneChunks>(context, chunk_size, degree, half);
    }
    frame.ensure_gaussians(chunk_size);
    frame.ensure_entries(entries_for(chunk_size));
    frame.ensure_image(pixels, tiles);
    frame.ensure_readback(pixels);
    frame.ensure_carry(pixels);
    if (with_stats) {
        frame.ensure_stats(chunk_size);
        gathered = {};
        gathered.resize(input_count);
    }

    // Ranges of `order`, front to back. Each chunk is two submissions: the passes up to the tile
    // ranges, then, once its tile entries are known to fit, the blend. A chunk whose entries
    // overflow is sorted again with more entries, or split in two where more would not fit the
    // budget; the carried state is untouched until its blend.
    std::deque<std::pair<uint32_t, uint32_t>> pending;
    for (uint32_t c = 0; c < std::max(chunk_count, 1u); ++c)
        pending.emplace_back(c * chunk_size, std::min(drawable, (c + 1) * chunk_size));
    const VkDeviceSize counters_offset = readback_counters_offset(pixels, read_back);
    uint32_t drawn = 0;
    while (!pending.empty()) {
        const auto [begin, end] = pending.front();
        pending.pop_front();
        std::vector<uint32_t> indices(order.begin() + begin, order.begin() + end);
        std::sort(indices.begin(), indices.end());
        chunks->stage(host, indices);
        const auto params = render::make_camera_params(camera, settings, chunks->device.count, degree, half,
                                                       frame.entry_capacity);
        stats.tile_key_bits = render::tile_key_bits(params.size[2] * params.size[3]);
        stream.begin();
        chunks->record_upload(stream);
        record_tiles(stream, params, chunks->device, with_stats);
        stream.copy(frame.counters, frame.readback, render::kCounterCount * sizeof(uint32_t), 0, counters_offset);
        stream.submit_and_wait();
        add_stage_times();
        uint32_t counters[render::kCounterCount];
        std::memcpy(counters, static_cast<const char*>(frame.readback.mapped()) + counters_offset, sizeof(counters));
        const uint32_t needed = counters[render::kCounterEntriesNeeded];
        const uint32_t count = end - begin;
        if (needed >= gpu::PrefixScan::saturated_sum && count > 1) {
            // Counted only as "at least" (whatever the capacity): split the chunk until each half
            // can be counted.
            ++stats.attempts;
            pending.emplace_front(begin + count / 2, end);
            pending.emplace_front(begin, begin + count / 2);
            continue;
        }
        render::check_entries_sortable(needed);
        if (needed > frame.entry_capacity) {
            ++stats.attempts;
            chunk_entries_per_gaussian = std::max(chunk_entries_per_gaussian, needed * render::kEntryGrowth / count);
            const uint32_t grown = render::grown_entry_capacity(needed);
            if (held_with(chunks->capacity, grown) <= budget) {
                frame.ensure_entries(grown);
                pending.emplace_front(begin, end);
            } else if (held_with(chunks->capacity, needed) <= budget) {
                frame.ensure_entries(needed);
                pending.emplace_front(begin, end);
            } else if (count > 1) {
                pending.emplace_front(begin + count / 2, end);
                pending.emplace_front(begin, begin + count / 2);
            } else {
                throw GpuError("memory budget of " + mebibytes(budget) + " is too small: one Gaussian needs " +
                               std::to_string(needed) + " tile entries in this view; raise --memory-budget");
            }
            continue;
        }

        const bool last = pending.empty();
        const uint32_t flags = (drawn > 0 ? shader::render::CARRY_LOAD : 0u) | (last ? shader::render::CARRY_LAST : 0u);
        stream.begin();
        record_blend_pass(stream, params.size[2], params.size[3], with_stats, &flags);
        if (with_stats) copy_stats(stream, count);
        if (last && read_back) copy_image_to_readback(stream, pixels);
        stream.submit_and_wait();
        add_stage_times();
        if (with_stats) unpack_stats(count, indices.data(), gathered);
        stats.visible += counters[render::kCounterVisible];
        stats.tile_entries += needed;
        ++drawn;
    }
    stats.chunks = drawn;
    stats.scene_bytes = scene_device_bytes();
    stats.device_bytes = frame.device_bytes() + stats.scene_bytes;
}

const gpu::Kernel<shader::render::PackRgba8Kernel>& Renderer::Impl::pack_kernel() {
    if (!pack_rgba8) pack_rgba8 = std::make_unique<gpu::Kernel<shader::render::PackRgba8Kernel>>(context);
    return *pack_rgba8;
}

void Renderer::Impl::wait_for_recorded_frames() const {
    if (recorded) gpu::vk(context).vkQueueWaitIdle(context.queue());
}

void Renderer::Impl::record_into(VkCommandBuffer command_buffer, const Camera& camera, const RenderSettings& settings,
                                 const RenderTarget& target) {
    if (settings.gather_stats)
        throw std::invalid_argument("Renderer::record does not gather per-Gaussian statistics; use render()");
    if (!scene.params)
        throw GpuError("Renderer::record: the scene does not fit the memory budget of " + mebibytes(budget) +
                       " and a recorded frame cannot be split into chunks; use render(), or a larger budget");
    const uint32_t pixel_bytes = render_target_pixel_bytes(target.format);
    if (pixel_bytes == 0)
        throw std::invalid_argument("Renderer::record: VkFormat " + std::to_string(target.format) +
                                    " is not one of the target formats (render/render_target.hpp)");
    if ((target.image != VK_NULL_HANDLE) == (target.buffer != VK_NULL_HANDLE))
        throw std::invalid_argument("Renderer::record: set exactly one of RenderTarget::image and ::buffer");
    camera.validate();
    const auto [pixels, tiles] = render::image_extent(camera);
    const bool packs = pixel_bytes == 4;

    // The last recorded frame that finished says how many tile entries its view needed.
    uint32_t entries = frame.entry_capacity > 0 ? frame.entry_capacity
                                                : std::max(scene.count, 1u) * render::kInitialEntriesPerGaussian;
    stats = {};
    stats.gaussians = scene.count;
    if (recorded) {
        uint32_t counters[render::kCounterCount];
        std::memcpy(counters, frame.recorded_counters.mapped(), sizeof(counters));
        stats.visible = counters[render::kCounterVisible];
        stats.tile_entries = counters[render::kCounterEntriesNeeded];
        render::check_entries_sortable(stats.tile_entries);
        if (stats.tile_entries > entries)
            entries = render::grown_entry_capacity(stats.tile_entries);
    }
    if (!frame.fits(scene.count, pixels, tiles, entries) || (packs && pixels > frame.packed_capacity)) {
        wait_for_recorded_frames();  // pending frames still use the buffers about to be replaced
        frame.ensure_gaussians(scene.count);
        frame.ensure_image(pixels, tiles);
        frame.ensure_entries(entries);
        if (packs) frame.ensure_packed(pixels);
    }

    const auto params =
        render::make_camera_params(camera, settings, scene.count, scene.sh_degree, scene.half_sh, frame.entry_capacity);
    stats.tile_key_bits = render::tile_key_bits(params.size[2] * params.size[3]);
    gpu::CommandStream out(context, gpu::CommandStream::Recording{command_buffer});
    out.barrier_after_everything();
    record_passes(out, params, scene, false);
    const gpu::Buffer* source = &frame.color_alpha;
    if (packs) {
        const bool bgra = target.format == VK_FORMAT_B8G8R8A8_UNORM || target.format == VK_FORMAT_B8G8R8A8_SRGB;
        out.dispatch(pack_kernel(),
                     {.color_alpha = frame.color_alpha.address(),
                      .packed = frame.packed.address(),
                      .pixels = pixels,
                      .bgra = bgra ? 1u : 0u},
                     gpu::groups_for(pixels));
        out.barrier();
        source = &frame.packed;
    }
    render::record_target_copy(out, *source, target, static_cast<uint32_t>(camera.width),
                               static_cast<uint32_t>(camera.height));
    out.copy(frame.counters, frame.recorded_counters, render::kCounterCount * sizeof(uint32_t));
    out.barrier_before_host_read();
    recorded = true;
    stats.scene_bytes = scene.params.size() + scene.sh.size();
    stats.device_bytes = frame.device_bytes() + stats.scene_bytes;
}

Renderer::Renderer(const gpu::Context& context) : impl_(std::make_unique<Impl>(context)) {}
Renderer::~Renderer() { impl_->wait_for_recorded_frames(); }

void Renderer::Impl::copy_stats(gpu::CommandStream& stream, uint32_t count) {
    // Layout of the readback: means_depth (vec4 with the radius, 0 when the reference would cull),
    // weight (uint64), max weight, pixels, centre weight; each array `count` long.
    const uint64_t g = count;
    auto& f = frame;
    stream.copy(f.means_depth, f.stats_readback, g * 16, 0, 0);
    stream.copy(f.stat_weight, f.stats_readback, g * 8, 0, g * 16);
    stream.copy(f.stat_max_weight, f.stats_readback, g * 4, 0, g * 24);
    stream.copy(f.stat_pixels, f.stats_readback, g * 4, 0, g * 28);
    stream.copy(f.stat_centre_weight, f.stats_readback, g * 4, 0, g * 32);
}

void Renderer::Impl::unpack_stats(uint32_t count, const uint32_t* uploaded, GaussianStats& out) const {
    const size_t n = count;
    const auto* base = static_cast<const char*>(frame.stats_readback.mapped());
    const auto* means = reinterpret_cast<const float*>(base);
    const auto* weight = reinterpret_cast<const uint64_t*>(base + n * 16);
    const auto* max_weight = reinterpret_cast<const float*>(base + n * 24);
    const auto* pixels = reinterpret_cast<const uint32_t*>(base + n * 28);
    const auto* centre_weight = reinterpret_cast<const float*>(base + n * 32);
    for (size_t i = 0; i < n; ++i) {
        const size_t in_scene = uploaded ? uploaded[i] : i;
        const size_t at = kept_indices.empty() ? in_scene : kept_indices[in_scene];
        out.visible[at] = means[i * 4 + 3] > 0.0f;
        if (out.visible[at]) {
            out.screen_x[at] = means[i * 4 + 0];
            out.screen_y[at] = means[i * 4 + 1];
            out.depth[at] = means[i * 4 + 2];
            out.radius[at] = means[i * 4 + 3];
        }
        out.blend_weight[at] = double(weight[i]) / 4294967296.0;  // 32.32 fixed point
        out.max_weight[at] = max_weight[i];
        out.pixels[at] = pixels[i];
        out.centre_weight[at] = centre_weight[i];
    }
}

SanitizeReport Renderer::set_scene(const GaussianCloud& cloud, const SceneStorage& storage) {
    GaussianCloud copy = cloud;
    SanitizeReport report = sanitize(copy);
    auto& d = *impl_;
    d.wait_for_recorded_frames();
    d.scene = {};
    d.chunks.reset();
    d.host = render::HostScene::activate(std::move(copy));
    d.budget = storage.memory_budget > 0 ? storage.memory_budget : d.context.memory_budget();
    const bool budget_given = storage.memory_budget > 0 || d.context.impl().memory_budget > 0;
    // Whole on the device if the scene and its per-Gaussian frame buffers fit (the image's size
    // is not known yet: each frame checks again). Otherwise, or when the budget was given (so a
    // frame may need chunks later), the host copy stays for chunked frames.
    const uint32_t n = d.host.count;
    const uint32_t entries = std::max(n, 1u) * render::kInitialEntriesPerGaussian;
    const bool fits = render::GpuScene::bytes_for(n, d.host.sh_degree, storage.half_sh) +
                          d.projected_frame_bytes(n, entries, 1, 1, false, false) <=
                      d.budget;
    if (fits) d.scene = render::GpuScene::upload(d.context, d.host, storage);
    d.scene.count = n;
    d.scene.sh_degree = d.host.sh_degree;
    d.scene.half_sh = storage.half_sh;
    d.chunk_entries_per_gaussian = render::kInitialEntriesPerGaussian;
    d.has_host = !fits || budget_given;
    if (!d.has_host) d.host = {};
    impl_->input_count = cloud.size();
    impl_->kept_indices = report.kept_indices;
    return report;
}

size_t Renderer::scene_size() const { return impl_->scene.count; }

RenderOutput Renderer::render(const Camera& camera, const RenderSettings& settings) {
    impl_->run(camera, settings, true);
    RenderOutput out;
    out.width = camera.width;
    out.height = camera.height;
    const size_t pixels = size_t(camera.width) * camera.height;
    const auto* base = static_cast<const char*>(impl_->frame.readback.mapped());
    const auto* color_alpha = reinterpret_cast<const float*>(base);
    out.rgb.resize(pixels * 3);
    out.alpha.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) out.rgb[i * 3 + c] = color_alpha[i * 4 + c];
        out.alpha[i] = color_alpha[i * 4 + 3];
    }
    out.depth.resize(pixels);
    std::memcpy(out.depth.data(), base + pixels * 16, pixels * 4);
    out.contributors.resize(pixels);
    std::memcpy(out.contributors.data(), base + pixels * 20, pixels * 4);
    if (settings.gather_stats) out.stats = std::move(impl_->gathered);
    return out;
}

void Renderer::render_gpu_only(const Camera& camera, const RenderSettings& settings) {
    impl_->run(camera, settings, false);
}

GaussianStats Renderer::render_stats(const Camera& camera, const RenderSettings& settings) {
    RenderSettings with_stats = settings;
    with_stats.gather_stats = true;
    impl_->run(camera, with_stats, false);
    return std::move(impl_->gathered);
}

GaussianTotals Renderer::render_stats_totals(const std::vector<Camera>& cameras, const RenderSettings& settings,
                                             const std::function<void(size_t, size_t)>& progress) {
    auto& d = *impl_;
    RenderSettings with_stats = settings;
    with_stats.gather_stats = true;
    GaussianTotals totals;
    totals.resize(d.input_count);
    std::optional<render::StatsTotals> on_device;
    if (!d.has_host && d.scene.params) {
        d.stats_kernel();  // the device check
        if (!d.stats_totals)
            d.stats_totals = std::make_unique<gpu::Kernel<shader::render::StatsTotalsKernel>>(d.context);
        on_device.emplace(d.context, *d.stats_totals, d.scene.count);
    }
    for (size_t v = 0; v < cameras.size(); ++v) {
        d.run(cameras[v], with_stats, false, on_device ? &*on_device : nullptr);
        if (!on_device) add_view(totals, d.gathered);
        ++totals.views;
        if (progress) progress(v + 1, cameras.size());
    }
    if (on_device) on_device->add_to(totals, d.kept_indices);
    return totals;
}

void Renderer::record(VkCommandBuffer command_buffer, const Camera& camera, const RenderSettings& settings,
                      const RenderTarget& target) {
    impl_->record_into(command_buffer, camera, settings, target);
}

const FrameStats& Renderer::last_frame() const { return impl_->stats; }

const gpu::Context& Renderer::context() const { return impl_->context; }

}  // namespace vksplat
