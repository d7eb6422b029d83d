// Replays the fuzz corpora through the readers in the normal build (no libFuzzer): every seed in
// tests/fuzz/seeds/<target>/ must read, and every input that once crashed, hung or exhausted memory
// (tests/fuzz/regressions/<target>/) must now read or be refused with InputError, never crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fuzz/fuzz_targets.hpp"

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
    for (const auto& input : files_in(kFuzzDir / "regressions" / GetParam().name)) {
        SCOPED_TRACE(input.string());
        try {
            GetParam().read(scratch, contents(input));
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
