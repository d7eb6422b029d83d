#pragma once
// Where the real-scene data lives, and a skip for tests that need it.
#include <gtest/gtest.h>

#include <filesystem>

namespace vksplat::test {

// ../shared/data beside the checkout (VKSPLAT_SHARED_DATA env var overrides it).
std::filesystem::path shared_data_dir();
bool shared_data_available();

}  // namespace vksplat::test

// Skips the current test with a message naming the missing folder.
#define VKSPLAT_REQUIRE_SHARED_DATA()                                                       \
    do {                                                                                    \
        if (!::vksplat::test::shared_data_available())                                      \
            GTEST_SKIP() << "real-scene data not found at "                                 \
                         << ::vksplat::test::shared_data_dir().string()                     \
                         << " (set VKSPLAT_SHARED_DATA to its location to run this test)";  \
    } while (0)
