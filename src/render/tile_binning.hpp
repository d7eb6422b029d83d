#pragma once
// TileBinning: every pass of a frame before the blend, from the scene's parameters to each tile's
// depth-ordered list of splats: preprocess (which also keys every Gaussian for the depth sort, the
// culled ones last), the depth sort, the tile entries, the stable tile sort and the tile ranges.
// The renderer and the trainer both record it, then blend (and the trainer differentiates) what
// it leaves in the FrameResources. Its kernels: shaders/render/{preprocess,clear_words,
// indirect_args,emit_tile_entries,tile_ranges}.comp, their layouts in shaders/render/tile_binning.h.
#include <cstdint>
#include <memory>

#include "gpu/command_stream.hpp"
#include "gpu/kernel.hpp"
#include "gpu/prefix_scan.hpp"
#include "gpu/radix_sort.hpp"
#include "render/frame_layout.hpp"
#include "render/frame_resources.hpp"

namespace vksplat::shader::render {
struct PreprocessPush;
struct ClearWordsKernel;
struct IndirectArgsKernel;
struct EmitTileEntriesKernel;
struct TileRangesKernel;
}  // namespace vksplat::shader::render

namespace vksplat::render {

// The scene a frame reads. `params` as the preprocess kernel reads them: for the renderer's,
// GpuScene's activated layout, possibly inside larger buffers, 3 vec4 per Gaussian: (position,
// opacity), (scale, 0), (quaternion w, x, y, z); for the trainer's, its raw parameters.
struct SceneAddresses {
    VkDeviceAddress params = 0;
    VkDeviceAddress sh = 0;      // [Gaussian][coefficient][rgb], float or packed halves
    uint32_t count = 0;
};

// Bits of the tile sort's keys. They cover the padding id (= tile count) too, which sorts after
// every real tile.
uint32_t tile_key_bits(uint32_t tiles);

// Throws GpuError when a view's counted tile entries (kCounterEntriesNeeded) are more than one frame
// can sort: the scan that counts them saturates, so from PrefixScan::saturated_sum up the count
// is only a lower bound, and a frame sized by it would drop entries unseen.
void check_entries_sortable(uint32_t needed);

class TileBinning {
public:
    using PreprocessPipeline = gpu::PushKernel<shader::render::PreprocessPush>;
    // With the renderer's preprocess (shaders/render/preprocess.comp).
    explicit TileBinning(const gpu::Context& context);
    // With another preprocess of the same push and outputs: the trainer's reads its raw parameters
    // (shaders/train/preprocess_trainable.comp).
    TileBinning(const gpu::Context& context, std::unique_ptr<PreprocessPipeline> preprocess);
    ~TileBinning();

    // Records the camera and counter uploads and the passes up to the tile ranges into `stream`,
    // working in `frame` (sized for the scene, the image and params.entry_capacity entries by the
    // caller). Ends with a barrier: the ranges, the entries and the per-splat arrays are ready.
    // Entries beyond the capacity are dropped; the caller compares the counter
    // kCounterEntriesNeeded with the capacity after the submission.
    void record(gpu::CommandStream& stream, FrameResources& frame, const CameraParams& params,
                const SceneAddresses& scene) const;

private:
    std::unique_ptr<gpu::Kernel<shader::render::ClearWordsKernel>> clear_words_;
    std::unique_ptr<PreprocessPipeline> preprocess_;
    std::unique_ptr<gpu::Kernel<shader::render::IndirectArgsKernel>> indirect_args_;
    std::unique_ptr<gpu::Kernel<shader::render::EmitTileEntriesKernel>> emit_tile_entries_;
    std::unique_ptr<gpu::Kernel<shader::render::TileRangesKernel>> tile_ranges_;
    gpu::PrefixScan scan_;
    gpu::RadixSort sort_;
};

}  // namespace vksplat::render
