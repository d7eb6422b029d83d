#include "render/entry_growth.hpp"

#include <algorithm>
#include <cmath>

#include "vksplat/error.hpp"

namespace vksplat::render {

uint32_t grown_entry_capacity(uint32_t needed) {
    return static_cast<uint32_t>(std::min(std::ceil(needed * kEntryGrowth), double(0x7fffffffu)));
}

void check_frame_attempts(uint32_t attempts, const std::string& what) {
    if (attempts >= kMaxFrameAttempts)
        throw GpuError(what + " still needs more tile entries after " + std::to_string(kMaxFrameAttempts) + " attempts");
}

}  // namespace vksplat::render
