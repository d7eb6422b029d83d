// The libFuzzer entry point for one reader, chosen at build time by VKSPLAT_FUZZ_TARGET (see
// tests/fuzz/CMakeLists.txt). InputError is the reader's correct answer to bad bytes; any other
// exception escapes, and libFuzzer reports it as a crash along with what the sanitizers find.
#include <cstdint>
#include <cstdlib>
#include <cstdio>

#include "fuzz/fuzz_targets.hpp"

namespace {

const vksplat::fuzz::FuzzTarget& target() {
    static const vksplat::fuzz::FuzzTarget* found = vksplat::fuzz::find_fuzz_target(VKSPLAT_FUZZ_TARGET);
    if (!found) {
        std::fprintf(stderr, "no fuzz target named %s\n", VKSPLAT_FUZZ_TARGET);
        std::abort();
    }
    return *found;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const vksplat::fuzz::ScratchFolder scratch;
    try {
        target().read(scratch, std::string_view(reinterpret_cast<const char*>(data), size));
    } catch (const vksplat::InputError&) {
    }
    return 0;
}
