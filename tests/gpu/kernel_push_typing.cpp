// Compiled, never run, by two ctest entries (tests/CMakeLists.txt): gpu_kernel_push_matches must
// compile, gpu_kernel_push_mismatch (PUSH_MISMATCH defined) must not, because
// CommandStream::dispatch takes a gpu::Kernel<K> only with a K::Push. RadixSetupPush and
// ScanSetupPush have the same members in the same order, so only their types tell them apart.
#include "gpu/command_stream.hpp"
#include "shaders/sort/radix_setup.kernel.hpp"
#include "shaders/sort/scan_setup.kernel.hpp"

namespace vksplat::gpu {

void record_setup(CommandStream& stream, const Kernel<shader::sort::RadixSetupKernel>& kernel) {
#ifdef PUSH_MISMATCH
    const shader::sort::ScanSetupPush push{.count = 0, .control = 0, .capacity = 1, .block = 1};
#else
    const shader::sort::RadixSetupPush push{.count = 0, .control = 0, .capacity = 1, .block = 1};
#endif
    stream.dispatch(kernel, push, 1);
}

}  // namespace vksplat::gpu
