// Replays the fuzz corpora through the readers in the normal build (no libFuzzer): every seed in
// tests/fuzz/seeds/<target>/ must read, and every hostile input (tests/fuzz/regressions/<target>/:
// inputs that crashed, hung or exhausted memory, and inputs aimed at the checks that keep a reader
// from doing so) must read or be refused with InputError, never crash, and within a memory cap.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fuzz/fuzz_targets.hpp"

// AddressSanitizer: GCC says so with __SANITIZE_ADDRESS__, clang through __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define VKSPLAT_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VKSPLAT_ADDRESS_SANITIZER 1
#endif
#endif

namespace vksplat::fuzz {
namespace {

const std::filesystem::path kFuzzDir = std::filesystem::path(VKSPLAT_SOURCE_DIR) / "tests" / "fuzz";

std::vector<std::filesystem::path> files_in(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(folder))
        for (const auto& entry : std::filesystem::directory_iterator(folder))
            if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::string contents(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

// Lowers the address-space limit to what the process maps now plus 1 GiB for its lifetime, so that
// an input that makes a reader allocate far beyond the file's size fails here with std::bad_alloc
// instead of passing on a machine with memory to spare. Under AddressSanitizer, whose shadow memory
// is terabytes of address space, it does nothing: there libFuzzer's -malloc_limit_mb (tools/fuzz.sh)
// catches such inputs.
class AddressSpaceCap {
public:
    AddressSpaceCap() {
#ifndef VKSPLAT_ADDRESS_SANITIZER
        size_t pages = 0;
        std::ifstream("/proc/self/statm") >> pages;
        if (pages == 0 || getrlimit(RLIMIT_AS, &saved_) != 0) return;
        rlimit capped = saved_;
        capped.rlim_cur = std::min<rlim_t>(saved_.rlim_cur, pages * sysconf(_SC_PAGESIZE) + (rlim_t{1} << 30));
        active_ = setrlimit(RLIMIT_AS, &capped) == 0;
#endif
    }
    ~AddressSpaceCap() {
        if (active_) setrlimit(RLIMIT_AS, &saved_);
    }
    AddressSpaceCap(const AddressSpaceCap&) = delete;
    AddressSpaceCap& operator=(const AddressSpaceCap&) = delete;

private:
    rlimit saved_{};
    bool active_ = false;
};

class FuzzCorpus : public ::testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzCorpus, EverySeedReads) {
    const ScratchFolder scratch;
    const auto seeds = files_in(kFuzzDir / "seeds" / GetParam().name);
    ASSERT_FALSE(seeds.empty()) << "no seeds for " << GetParam().name;
    for (const auto& seed : seeds) {
        try {
            GetParam().read(scratch, contents(seed));
        } catch (const std::exception& error) {
            ADD_FAILURE() << seed << ": " << error.what();
        }
    }
}

TEST_P(FuzzCorpus, EveryRegressionInputReadsOrIsRefusedWithInputError) {
    const ScratchFolder scratch;
    const auto folder = kFuzzDir / "regressions" / GetParam().name;
    const auto inputs = files_in(folder);
    // Every reader has hostile inputs (tests/fuzz/make_regressions.py); none here means the folder
    // was lost or renamed, and the test would pass on nothing.
    ASSERT_FALSE(inputs.empty()) << "no regression inputs for " << GetParam().name << ": " << folder
                                 << " is missing or empty (see tests/fuzz/regressions/README.md)";
    for (const auto& input : inputs) {
        const std::string bytes = contents(input);
        const AddressSpaceCap cap;
        try {
            GetParam().read(scratch, bytes);
        } catch (const InputError&) {
        } catch (const std::exception& error) {
            ADD_FAILURE() << input << " threw something other than InputError: " << error.what();
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Readers, FuzzCorpus, ::testing::ValuesIn(fuzz_targets()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vksplat::fuzz
