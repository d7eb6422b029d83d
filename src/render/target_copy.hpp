#pragma once
// The last step of Renderer::record: the finished picture into the application's image or buffer,
// with the barriers render/render_target.hpp promises.
#include "gpu/command_stream.hpp"
#include "vksplat/render/render_target.hpp"

namespace vksplat::render {

// Copies width x height pixels of `source` (tightly packed, in the target's pixel layout) into
// `target`, with the layout transitions and barriers of the contract.
void record_target_copy(gpu::CommandStream& stream, const gpu::Buffer& source, const RenderTarget& target,
                        uint32_t width, uint32_t height);

}  // namespace vksplat::render
