#include "gpu/transfer.hpp"

#include <cstring>

#include "gpu/command_stream.hpp"

namespace vksplat::gpu {

Buffer upload_buffer(const Context& context, const void* data, size_t bytes, std::string name) {
    Buffer device(context, bytes, MemoryKind::device, name);
    if (bytes == 0) return device;
    Buffer staging(context, bytes, MemoryKind::upload, name + " (staging)");
    std::memcpy(staging.mapped(), data, bytes);
    CommandStream stream(context, 0);
    stream.begin();
    stream.copy(staging, device, bytes);
    stream.submit_and_wait();
    return device;
}

void read_buffer(const Context& context, const Buffer& buffer, void* out, size_t bytes) {
    if (bytes == 0) return;
    Buffer staging(context, bytes, MemoryKind::readback, buffer.name() + " (readback)");
    CommandStream stream(context, 0);
    stream.begin();
    stream.copy(buffer, staging, bytes);
    stream.submit_and_wait();
    std::memcpy(out, staging.mapped(), bytes);
}

}  // namespace vksplat::gpu
