#include "train/loss_passes.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "shaders/train/loss.kernel.hpp"

namespace vksplat::train {
namespace {

constexpr uint32_t kTileWidth = shader::train::LOSS_TILE_WIDTH;
constexpr uint32_t kTileHeight = shader::train::LOSS_TILE_HEIGHT;
constexpr uint32_t kSegmentTiles = shader::train::LOSS_SEGMENT_TILES;
constexpr uint32_t kMaxGroups = shader::MAX_GROUPS_X;  // the kernel walks its work in a grid-stride loop

// The sums of one workgroup, as the kernel writes them (a vec4).
struct Partial {
    float l1, ssim, mse, unused;
};

}  // namespace

struct LossPasses::Impl {
    const gpu::Context& context;
    gpu::Kernel<shader::train::LossKernel> kernel;
    gpu::Buffer partials;          // device scratch, grown to the largest image recorded
    // Per readback slot: the partials of the last record() into it, and what last() needs of it.
    struct Readback {
        gpu::Buffer partials;
        uint32_t groups = 0;
        double pixel_channels = 0;  // 3 * width * height
        double ssim_weight = 0;
    };
    std::array<Readback, LossPasses::kReadbackSlots> readbacks;

    explicit Impl(const gpu::Context& c)
        : context(c),
          kernel(c) {}
};

LossPasses::LossPasses(const gpu::Context& context) : impl_(std::make_unique<Impl>(context)) {}

LossPasses::~LossPasses() = default;

void LossPasses::record(gpu::CommandStream& stream, const LossInputs& inputs, int slot) {
    const uint64_t pixels = uint64_t(inputs.width) * inputs.height;
    if (pixels == 0) throw std::invalid_argument("training loss: the image is empty");
    // The kernel indexes pixels with 32-bit integers.
    if (pixels > UINT32_MAX)
        throw std::invalid_argument("training loss: " + std::to_string(inputs.width) + " x " +
                                    std::to_string(inputs.height) + " pixels is too large an image");
    Impl& d = *impl_;
    const uint32_t tiles_x = (inputs.width + kTileWidth - 1) / kTileWidth;
    const uint32_t tiles_y = (inputs.height + kTileHeight - 1) / kTileHeight;
    const uint32_t strips = tiles_x * ((tiles_y + kSegmentTiles - 1) / kSegmentTiles);
    const uint32_t groups = std::min(3 * strips, kMaxGroups);  // a workgroup per channel of a strip
    gpu::reserve(d.partials, d.context, groups * sizeof(Partial), gpu::MemoryKind::device, "loss partial sums");
    Impl::Readback& readback = d.readbacks.at(size_t(slot));
    gpu::reserve(readback.partials, d.context, groups * sizeof(Partial), gpu::MemoryKind::readback, "loss sums readback");
    readback.groups = groups;
    readback.pixel_channels = 3.0 * double(pixels);
    readback.ssim_weight = inputs.ssim_weight;

    const shader::train::LossPush push{
        .rendered = inputs.rendered,
        .photo = inputs.photo,
        .partials = d.partials.address(),
        .gradient = inputs.gradient,
        .width = inputs.width,
        .height = inputs.height,
        .tiles_x = tiles_x,
        .tiles_y = tiles_y,
        .strips = strips,
        .ssim_weight = inputs.ssim_weight,
        .inv_count = float(1.0 / readback.pixel_channels),
    };
    stream.dispatch(d.kernel, push, groups);
    stream.barrier();
    stream.copy(d.partials, readback.partials, groups * sizeof(Partial));
    stream.barrier_before_host_read();
}

LossValue LossPasses::last(int slot) const {
    const Impl::Readback& d = impl_->readbacks.at(size_t(slot));
    if (d.groups == 0) return {};
    // In double, in workgroup order: the same sums on every run.
    const auto* partials = static_cast<const Partial*>(d.partials.mapped());
    double l1 = 0, ssim = 0, mse = 0;
    for (uint32_t g = 0; g < d.groups; ++g) {
        l1 += partials[g].l1;
        ssim += partials[g].ssim;
        mse += partials[g].mse;
    }
    LossValue value;
    value.l1 = l1 / d.pixel_channels;
    value.ssim = ssim / d.pixel_channels;
    value.mse = mse / d.pixel_channels;
    value.loss = (1.0 - d.ssim_weight) * value.l1 + d.ssim_weight * (1.0 - value.ssim);
    return value;
}

uint64_t LossPasses::device_bytes() const { return impl_->partials.size(); }

}  // namespace vksplat::train
