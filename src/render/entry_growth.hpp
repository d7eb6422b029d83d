#pragma once
// How a frame's tile-entry buffers grow: one policy for the renderer (whole frames, chunks,
// recorded frames) and the trainer. A frame learns how many (tile, splat) entries it needs only
// when it runs; one that needs more than its buffers hold is run again with them grown to that
// count and a quarter more (headroom, so that the next views rarely grow them again), a bounded
// number of times.
#include <cstdint>
#include <string>

namespace vksplat::render {

// Capacity to start with: a few tiles per Gaussian covers typical scenes.
inline constexpr uint32_t kInitialEntriesPerGaussian = 4;
inline constexpr double kEntryGrowth = 1.25;
// A frame run this often that still needs more entries is not settling on a count: a bug to
// report, not a size to grow to.
inline constexpr uint32_t kMaxFrameAttempts = 8;

// The capacity for a frame that counted `needed` entries: needed * kEntryGrowth rounded up, at
// most what the sort's 31-bit counts hold.
uint32_t grown_entry_capacity(uint32_t needed);

// Throws GpuError naming `what` (the view) once a frame has been run kMaxFrameAttempts times.
void check_frame_attempts(uint32_t attempts, const std::string& what);

}  // namespace vksplat::render
