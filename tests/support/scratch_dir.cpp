#include "support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

namespace vksplat::test {

std::filesystem::path fresh_test_dir(const std::string& prefix) {
    const auto dir = std::filesystem::temp_directory_path() /
                     (prefix + std::to_string(::getpid()) + "_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace vksplat::test
